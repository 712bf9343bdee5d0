//! Helpers shared by the integration tests: small irregular quad meshes and brute force.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use nalgebra::Point3;
use tilepattern::mesh::PolyMesh;

/// Runs the `tilepattern` command line with `args`.
pub fn tilepattern(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tilepattern"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// Runs the `tilepattern` command line with `args` on at most `threads` threads
/// (`TILEPATTERN_THREADS`), and fails the test unless it succeeds.
pub fn tilepattern_on_threads(threads: &str, args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_tilepattern"))
        .env("TILEPATTERN_THREADS", threads)
        .args(args)
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// An empty scratch folder for the test `name` (of this test process).
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("tp-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The JSON file at `path`.
pub fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// `path` as a command-line argument.
pub fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// Splits every face into quads through its centroid and edge midpoints (one Catmull-Clark
/// topology step without smoothing): an n-gon becomes n quads, and its centre an interior
/// vertex of valence n.
pub fn split_into_quads(mesh: &PolyMesh) -> PolyMesh {
    let mut positions: Vec<Point3<f64>> = mesh.positions().to_vec();
    let mut midpoint = std::collections::BTreeMap::new();
    let mut faces = Vec::new();
    for (f, face) in mesh.faces().iter().enumerate() {
        let centre = positions.len();
        positions.push(mesh.face_centroid(f));
        let n = face.len();
        let mut mid = |a: usize, b: usize, positions: &mut Vec<Point3<f64>>| -> usize {
            *midpoint.entry((a.min(b), a.max(b))).or_insert_with(|| {
                positions.push(nalgebra::center(&positions[a], &positions[b]));
                positions.len() - 1
            })
        };
        for i in 0..n {
            let prev = face[(i + n - 1) % n];
            let (v, next) = (face[i], face[(i + 1) % n]);
            let m_in = mid(prev, v, &mut positions);
            let m_out = mid(v, next, &mut positions);
            faces.push(vec![v, m_out, centre, m_in]);
        }
    }
    PolyMesh::new(positions, faces).unwrap()
}

/// A regular polygon with `n` corners as one face, in the xy plane.
pub fn polygon(n: usize) -> PolyMesh {
    let positions = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            Point3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    PolyMesh::new(positions, vec![(0..n).collect()]).unwrap()
}

/// Every matching of the candidate tiles `tiles` (as face pairs) over `face_count` faces.
pub fn all_matchings(face_count: usize, tiles: &[[usize; 2]]) -> Vec<Vec<bool>> {
    fn go(
        k: usize,
        tiles: &[[usize; 2]],
        used: &mut [bool],
        chosen: &mut Vec<bool>,
        out: &mut Vec<Vec<bool>>,
    ) {
        if k == tiles.len() {
            out.push(chosen.clone());
            return;
        }
        chosen.push(false);
        go(k + 1, tiles, used, chosen, out);
        chosen.pop();
        let [a, b] = tiles[k];
        if !used[a] && !used[b] {
            used[a] = true;
            used[b] = true;
            chosen.push(true);
            go(k + 1, tiles, used, chosen, out);
            chosen.pop();
            used[a] = false;
            used[b] = false;
        }
    }
    let mut out = Vec::new();
    go(
        0,
        tiles,
        &mut vec![false; face_count],
        &mut Vec::new(),
        &mut out,
    );
    out
}

/// True when every pair shares an edge of `mesh` and no face is used twice.
pub fn is_valid_matching(mesh: &PolyMesh, pairs: &[[usize; 2]]) -> bool {
    let mut used = vec![false; mesh.face_count()];
    pairs.iter().all(|&[a, b]| {
        let shared = mesh.faces()[a]
            .iter()
            .filter(|v| mesh.faces()[b].contains(v))
            .count();
        shared == 2
            && !std::mem::replace(&mut used[a], true)
            && !std::mem::replace(&mut used[b], true)
    })
}

/// `split_into_quads` applied `times` times: a quad mesh with the singular vertices of
/// `mesh`'s non-quad faces and vertices, each face split into `4^(times-1)` quads.
pub fn subdivided(mesh: &PolyMesh, times: usize) -> PolyMesh {
    (0..times).fold(mesh.clone(), |m, _| split_into_quads(&m))
}

/// Two pentagons and a triangle glued around a square: a disk whose split has interior
/// vertices of valence 3, 5 and 6 and a boundary with corners.
pub fn mixed_polygons() -> PolyMesh {
    let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
    let positions = vec![
        p(0.0, 0.0),
        p(1.0, 0.0),
        p(1.0, 1.0),
        p(0.0, 1.0),
        p(0.5, -0.8),
        p(1.8, 0.5),
        p(0.5, 1.8),
        p(-0.5, 1.6),
        p(-0.7, 0.5),
    ];
    let faces = vec![
        vec![0, 1, 2, 3],
        vec![0, 4, 1],
        vec![1, 5, 2],
        vec![2, 6, 3],
        vec![3, 7, 8, 0],
    ];
    PolyMesh::new(positions, faces).unwrap()
}

/// An `n` x `n` grid with a ragged boundary: every boundary face whose index passes a fixed
/// pseudo-random test is removed, as remeshers leave teeth along a shell's edge.
pub fn ragged_grid(n: usize) -> PolyMesh {
    let grid = tilepattern::mesh::generate::grid(n, n);
    let on_boundary = |f: usize| f % n == 0 || f % n == n - 1 || f / n == 0 || f / n == n - 1;
    let keep = |f: usize| !(on_boundary(f) && (f.wrapping_mul(2654435761) >> 7) % 3 == 0);
    let faces: Vec<Vec<usize>> = (0..grid.face_count())
        .filter(|&f| keep(f))
        .map(|f| grid.faces()[f].clone())
        .collect();
    PolyMesh::new(grid.positions().to_vec(), faces).unwrap()
}

/// Pairs of tiles whose kept faces overlap by more than `depth`, found by sampling, without
/// the library's own joint measure: points on a grid of pitch `step` over each tile's kept
/// face that lie at least `depth` inside it are looked up in every nearby tile's frame; a
/// point that also lies at least `depth` inside another tile's kept face (and within half a
/// tile width of its plane) is an overlap deeper than `depth` in both.
pub fn overlapping_tiles(
    tiles: &[tilepattern::tiles::Tile],
    depth: f64,
    step: f64,
) -> Vec<(usize, usize, Point3<f64>)> {
    use nalgebra::Vector3;
    let loops = |t: &tilepattern::tiles::Tile| -> Vec<Vec<[f64; 2]>> {
        let (hx, hy) = (t.size[0] / 2.0, t.size[1] / 2.0);
        match &t.cut {
            Some(cut) => cut.loops.clone(),
            None => vec![vec![[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]],
        }
    };
    // Depth of `q` inside `loops` (negative outside): winding number and distance to edges.
    let inside = |loops: &[Vec<[f64; 2]>], q: [f64; 2]| -> f64 {
        let (mut winding, mut nearest) = (0, f64::INFINITY);
        for l in loops {
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                let d = [b[0] - a[0], b[1] - a[1]];
                let len2 = d[0] * d[0] + d[1] * d[1];
                let t = if len2 > 0.0 {
                    (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                nearest = nearest.min((q[0] - a[0] - t * d[0]).hypot(q[1] - a[1] - t * d[1]));
                let side = d[0] * (q[1] - a[1]) - d[1] * (q[0] - a[0]);
                if a[1] <= q[1] && b[1] > q[1] && side > 0.0 {
                    winding += 1;
                } else if a[1] > q[1] && b[1] <= q[1] && side < 0.0 {
                    winding -= 1;
                }
            }
        }
        if winding != 0 { nearest } else { -nearest }
    };
    let all: Vec<Vec<Vec<[f64; 2]>>> = tiles.iter().map(loops).collect();
    let mut found = Vec::new();
    for (a, ta) in tiles.iter().enumerate() {
        let reach_a = ta.size[0].hypot(ta.size[1]) / 2.0;
        let near: Vec<usize> = (0..tiles.len())
            .filter(|&b| {
                b != a
                    && (tiles[b].frame.origin - ta.frame.origin).norm()
                        < reach_a + tiles[b].size[0].hypot(tiles[b].size[1]) / 2.0
            })
            .collect();
        let (hx, hy) = (ta.size[0] / 2.0, ta.size[1] / 2.0);
        let (nx, ny) = (
            (2.0 * hx / step).ceil() as usize,
            (2.0 * hy / step).ceil() as usize,
        );
        'points: for i in 0..=nx {
            for j in 0..=ny {
                let q = [
                    -hx + 2.0 * hx * i as f64 / nx as f64,
                    -hy + 2.0 * hy * j as f64 / ny as f64,
                ];
                if inside(&all[a], q) < depth {
                    continue;
                }
                let p = ta.to_world(Vector3::new(q[0], q[1], 0.0));
                for &b in &near {
                    let tb = &tiles[b];
                    let local = tb.frame.to_local(&p);
                    if local.z.abs() <= tb.size[1] / 2.0
                        && inside(&all[b], [local.x, local.y]) >= depth
                    {
                        found.push((a.min(b), a.max(b), p));
                        break 'points;
                    }
                }
            }
        }
    }
    found.sort_by_key(|f| (f.0, f.1));
    found.dedup_by_key(|f| (f.0, f.1));
    found
}

/// OBJ text of a flat 2 x 2 plate of `n` x `n` squares, each split into two triangles:
/// (n + 1)^2 vertices, 2 n^2 faces.
pub fn plate_obj(n: usize) -> String {
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (2.0 * i as f64 / n as f64, 2.0 * j as f64 / n as f64);
            text += &format!("v {x} {y} 0\n");
        }
    }
    let v = |i: usize, j: usize| i + (n + 1) * j + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
        }
    }
    text
}

/// The whole pipeline in level courses, as `tilepattern run` lays tiles: quads a course
/// high, a pattern stage of at most 5 s.
pub fn run_level(
    surface: &PolyMesh,
    spec: &tilepattern::tiles::TileSpec,
    finish: &tilepattern::tiles::FinishOptions,
) -> (tilepattern::remesh::Remeshed, tilepattern::pipeline::Tiling) {
    use tilepattern::pattern::{Courses, PatternOptions};
    use tilepattern::remesh::RemeshOptions;
    let options = {
        let mut o = PatternOptions::default();
        o.time_limit = std::time::Duration::from_secs(5);
        o.courses = Courses::Level {
            up: [0.0, 0.0, 1.0],
        };
        o
    };
    let remesh = {
        let mut o = RemeshOptions::default();
        o.target_edge = spec.quad_edge(true);
        o
    };
    tilepattern::pipeline::tile_surface(
        surface,
        &remesh,
        &options,
        spec,
        finish,
        &mut tilepattern::control::Control::none(),
    )
    .unwrap()
}
