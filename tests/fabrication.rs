//! Boundary tiles, cut list and laying order: tiles cut to the input surface's boundary
//! (outer edge and openings), grouped by cut shape and numbered in laying order.

use std::time::Duration;

use nalgebra::{Point3, Vector3};
use tilepattern::mesh::{PolyMesh, Topology, generate};
use tilepattern::pattern::{self, Bond, Pattern, PatternOptions};
use tilepattern::pipeline::{self, Tiling};
use tilepattern::tiles::{self, DropReason, FinishOptions, Tile, TileKind, TileSpec};

/// A flat quad lattice over `[x0, x1] x [y0, y1]` with `nx x ny` cells, lifted by `height`.
fn lattice(
    x: [f64; 2],
    y: [f64; 2],
    n: [usize; 2],
    height: impl Fn(f64, f64) -> f64,
) -> (Vec<Point3<f64>>, Vec<Vec<usize>>) {
    let mut positions = Vec::new();
    for j in 0..=n[1] {
        for i in 0..=n[0] {
            let (px, py) = (
                x[0] + (x[1] - x[0]) * i as f64 / n[0] as f64,
                y[0] + (y[1] - y[0]) * j as f64 / n[1] as f64,
            );
            positions.push(Point3::new(px, py, height(px, py)));
        }
    }
    let at = |i: usize, j: usize| i + (n[0] + 1) * j;
    let mut faces = Vec::new();
    for j in 0..n[1] {
        for i in 0..n[0] {
            faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (positions, faces)
}

/// Quads of `(positions, faces)` kept where `keep` holds at their centroid.
fn keep_faces(
    positions: Vec<Point3<f64>>,
    faces: Vec<Vec<usize>>,
    keep: impl Fn(&Point3<f64>) -> bool,
) -> PolyMesh {
    let centroid = |f: &Vec<usize>| {
        Point3::from(f.iter().map(|&v| positions[v].coords).sum::<Vector3<f64>>() / f.len() as f64)
    };
    let kept: Vec<Vec<usize>> = faces.into_iter().filter(|f| keep(&centroid(f))).collect();
    PolyMesh::new(positions, kept).unwrap()
}

/// The pattern made of exactly these pairs (the rest unpaired).
fn pattern_of(mesh: &PolyMesh, pairs: &[[usize; 2]]) -> Pattern {
    let mut found = pattern::solve(mesh, &{
        let mut o = PatternOptions::default();
        o.bond = Bond::Stack;
        o.time_limit = Duration::ZERO;
        o
    })
    .unwrap();
    found.pairs = pairs.to_vec();
    found.unpaired = (0..mesh.face_count())
        .filter(|f| !pairs.iter().any(|p| p.contains(f)))
        .collect();
    found
}

/// The tiles on the quad mesh's faces (not the filler pieces beyond it).
fn on_quads(tiling: &Tiling) -> Vec<&Tile> {
    tiling
        .tiles
        .iter()
        .filter(|t| !t.faces.is_empty())
        .collect()
}

const SQUARE: TileSpec = TileSpec {
    length: 2.0,
    width: 1.0,
    thickness: 0.1,
    joint: 0.0,
};

/// One 2 x 1 tile over two unit quads of `[0, 2] x [0, 1]`, cut to `surface`.
fn one_tile_on(surface: &PolyMesh) -> Tiling {
    let quads = generate::grid(2, 1);
    let finish = {
        let mut o = FinishOptions::for_spec(&SQUARE);
        o.min_kept_width = 0.05;
        o
    };
    pipeline::tiles_for_pattern(
        &quads,
        Some(surface),
        pattern_of(&quads, &[[0, 1]]),
        &SQUARE,
        &finish,
    )
    .unwrap()
}

#[test]
fn a_tile_over_the_edge_keeps_the_part_on_the_surface() {
    let (p, f) = lattice([0.0, 1.5], [-1.0, 2.0], [3, 6], |_, _| 0.0);
    let tiling = one_tile_on(&PolyMesh::new(p, f).unwrap());
    let on_quads = on_quads(&tiling);
    assert_eq!(on_quads.len(), 1);
    let tile = on_quads[0];
    assert_eq!(tile.kind, TileKind::Boundary);
    let cut = tile.cut.as_ref().unwrap();
    assert!((cut.kept_fraction - 0.75).abs() < 1e-9, "{cut:?}");
    assert_eq!(cut.loops.len(), 1);
    // In the tile's frame (x from face 0 to face 1) the kept part is [-1, 0.5] x [-0.5, 0.5].
    for point in &cut.loops[0] {
        assert!(
            point[0] >= -1.0 - 1e-9 && point[0] <= 0.5 + 1e-9 && point[1].abs() <= 0.5 + 1e-9,
            "{point:?}"
        );
    }
}

#[test]
fn an_opening_inside_a_tile_becomes_a_hole_in_its_outline() {
    let (p, f) = lattice([-1.0, 3.0], [-1.0, 2.0], [20, 15], |_, _| 0.0);
    let surface = keep_faces(p, f, |c| {
        !((0.8..1.2).contains(&c.x) && (0.4..0.6).contains(&c.y))
    });
    let tiling = one_tile_on(&surface);
    let cut = on_quads(&tiling)[0].cut.as_ref().unwrap();
    assert_eq!(cut.loops.len(), 2, "{cut:?}");
    assert!(
        (cut.area() - (2.0 - 0.4 * 0.2)).abs() < 1e-9,
        "{}",
        cut.area()
    );
    assert!(
        cut.loops.iter().any(|l| tiles::clip::signed_area(l) < 0.0),
        "the hole runs clockwise"
    );
}

#[test]
fn a_tile_off_the_surface_is_dropped_and_a_thin_strip_is_a_sliver() {
    let (p, f) = lattice([5.0, 6.0], [0.0, 1.0], [1, 1], |_, _| 0.0);
    let (q, g) = lattice([-1.0, 0.05], [-1.0, 2.0], [1, 3], |_, _| 0.0);
    let tiling_off = one_tile_on(&PolyMesh::new(p, f).unwrap());
    assert!(tiling_off.tiles.is_empty());
    assert_eq!(tiling_off.dropped[0].reason, DropReason::Outside);
    let tiling_thin = one_tile_on(&PolyMesh::new(q, g).unwrap());
    assert!(on_quads(&tiling_thin).is_empty());
    assert_eq!(tiling_thin.dropped[0].reason, DropReason::Sliver);
    let cutting = tiling_thin.report.cutting.as_ref().unwrap();
    assert_eq!(cutting.slivers.len(), 1);
    assert!((cutting.slivers[0].kept_area - 0.05).abs() < 1e-9);
}

/// A hypar `z = 0.3 x y` over `[-1, 1]^2`, as triangles, with an elliptic opening.
fn hypar_with_opening() -> PolyMesh {
    let (p, f) = lattice([-1.0, 1.0], [-1.0, 1.0], [60, 60], |x, y| 0.3 * x * y);
    let quads = keep_faces(p, f, |c| !in_opening(c.x, c.y));
    generate::triangulate_quads(&quads)
}

/// The opening: an ellipse off the centre (its edge a staircase of the 60 x 60 lattice).
fn in_opening(x: f64, y: f64) -> bool {
    ((x - 0.15) / 0.45).powi(2) + ((y + 0.1) / 0.3).powi(2) < 1.0
}

/// How far `p` lies outside the plan of `surface` (a height field over xy): its distance in
/// plan to the nearest face, 0 on a face.
fn outside_plan(surface: &PolyMesh, p: &Point3<f64>) -> f64 {
    let plan = |q: &Point3<f64>| [q.x, q.y];
    let q = plan(p);
    let mut best = f64::INFINITY;
    for face in surface.faces() {
        let corners: Vec<[f64; 2]> = face
            .iter()
            .map(|&v| plan(&surface.positions()[v]))
            .collect();
        let n = corners.len();
        let mut inside = true;
        for i in 0..n {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            let (d, e) = ([b[0] - a[0], b[1] - a[1]], [q[0] - a[0], q[1] - a[1]]);
            inside &= d[0] * e[1] - d[1] * e[0] >= 0.0;
            let t = ((e[0] * d[0] + e[1] * d[1]) / (d[0] * d[0] + d[1] * d[1])).clamp(0.0, 1.0);
            best = best.min((e[0] - t * d[0]).hypot(e[1] - t * d[1]));
        }
        if inside {
            return 0.0;
        }
    }
    best
}

/// The plan points of a tile's kept part: its outline, or its face's corners when uncut.
fn kept_points(tile: &Tile) -> Vec<Point3<f64>> {
    let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
    let local: Vec<[f64; 2]> = match &tile.cut {
        Some(cut) => cut.loops.iter().flatten().copied().collect(),
        None => vec![[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]],
    };
    local
        .iter()
        .map(|p| tile.to_world(Vector3::new(p[0], p[1], 0.0)))
        .collect()
}

/// Checks that no point of the surface lies deeper than `margin` inside two tiles' kept
/// faces (seen in each tile's frame).
fn assert_no_overlaps(surface: &PolyMesh, tiling: &Tiling, margin: f64) {
    for f in 0..surface.face_count() {
        let p = surface.face_centroid(f);
        let inside: Vec<usize> = (0..tiling.tiles.len())
            .filter(|&t| deep_inside(&tiling.tiles[t], &p, margin))
            .collect();
        let described: Vec<_> = inside
            .iter()
            .map(|&t| {
                (
                    t,
                    tiling.tiles[t].kind,
                    tiling.tiles[t].faces.clone(),
                    tiling.tiles[t].frame.origin,
                )
            })
            .collect();
        assert!(
            inside.len() <= 1,
            "surface point {p:?} lies in tiles {described:?}"
        );
    }
}

/// Whether `p` lies under `tile`'s kept face, at least `margin` from its edges.
fn deep_inside(tile: &Tile, p: &Point3<f64>, margin: f64) -> bool {
    let local = tile.frame.to_local(p);
    let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
    if local.x.abs() > hx - margin || local.y.abs() > hy - margin || local.z.abs() > hy {
        return false;
    }
    let Some(cut) = &tile.cut else { return true };
    let q = [local.x, local.y];
    let mut winding = 0;
    for l in &cut.loops {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let t = (((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / (d[0] * d[0] + d[1] * d[1]))
                .clamp(0.0, 1.0);
            if (q[0] - a[0] - t * d[0]).hypot(q[1] - a[1] - t * d[1]) < margin {
                return false;
            }
            let side = d[0] * (q[1] - a[1]) - d[1] * (q[0] - a[0]);
            if a[1] <= q[1] && b[1] > q[1] && side > 0.0 {
                winding += 1;
            } else if a[1] > q[1] && b[1] <= q[1] && side < 0.0 {
                winding -= 1;
            }
        }
    }
    winding != 0
}

/// Checks the promises of the fabrication output on a tiling of `surface`.
fn check_fabrication(surface: &PolyMesh, tiling: &Tiling, tolerance: f64) {
    for (t, tile) in tiling.tiles.iter().enumerate() {
        for p in kept_points(tile) {
            let off = outside_plan(surface, &p);
            assert!(
                off <= tolerance,
                "tile {t} ({:?}) reaches {p:?}, {off} off the surface",
                tile.kind
            );
        }
    }
    let counted: usize = tiling.cut_list.iter().map(|g| g.count).sum();
    assert_eq!(
        counted,
        tiling.tiles.len(),
        "the cut list counts every tile once"
    );
    for tile in &tiling.tiles {
        assert!(
            tiling
                .cut_list
                .iter()
                .any(|g| g.label == tile.label && g.kind == tile.kind),
            "label {}",
            tile.label
        );
    }
    let mut steps: Vec<usize> = tiling.tiles.iter().map(|t| t.step).collect();
    steps.sort_unstable();
    assert_eq!(
        steps,
        (0..tiling.tiles.len()).collect::<Vec<_>>(),
        "the laying order is a permutation"
    );
    let sequence = tiling.report.sequence.as_ref().unwrap();
    assert!(sequence.support_tiles > 0);
    let first = tiling.tiles.iter().find(|t| t.step == 0).unwrap();
    let lowest = tiling
        .tiles
        .iter()
        .map(|t| t.frame.origin.z)
        .fold(f64::INFINITY, f64::min);
    assert!(
        first.frame.origin.z <= lowest + 0.3,
        "the order starts at the supports, low down"
    );
}

/// Tiles for quads of edge 0.1: (0.19 + 0.01) / 2.
const SMALL: TileSpec = TileSpec {
    length: 0.19,
    width: 0.095,
    thickness: 0.01,
    joint: 0.01,
};

/// Quads of edge 0.1 over the hypar's whole square, ignoring the opening.
fn hypar_quads() -> PolyMesh {
    let (p, f) = lattice([-1.0, 1.0], [-1.0, 1.0], [20, 20], |x, y| 0.3 * x * y);
    PolyMesh::new(p, f).unwrap()
}

#[test]
fn tiles_on_a_hypar_with_an_opening_stay_on_the_surface_and_cover_it() {
    let surface = hypar_with_opening();
    let quads = hypar_quads();
    let spec = SMALL;
    let finish = FinishOptions::for_spec(&spec);
    let options = {
        let mut o = PatternOptions::default();
        o.time_limit = Duration::from_secs(5);
        o
    };
    let tiling = pipeline::tile_quad_mesh(
        &quads,
        Some(&surface),
        &options,
        &spec,
        &finish,
        &mut tilepattern::control::Control::none(),
    )
    .unwrap();
    let cutting = tiling.report.cutting.as_ref().unwrap();
    assert!(
        tiling.report.boundary_tiles >= 8,
        "tiles around the opening are cut: {}",
        tiling.report.boundary_tiles
    );
    assert!(
        cutting.outside_tiles + cutting.slivers.len() >= 3,
        "tiles over the opening are left out"
    );
    // Kept outlines lie on the surface, up to the flat tile's departure from the hypar.
    check_fabrication(&surface, &tiling, 0.002);
    // Tiles with their joints cover the surface but for the slivers left out at the opening
    // and the wide ends of wedge-shaped joints: 0.973 here measured at samples 1/2 of the
    // smallest tile side apart (0.978 by the face centroids of this 0.05-0.1 triangle mesh,
    // which saw fewer of the wedges).
    assert!(cutting.coverage >= 0.97, "coverage {}", cutting.coverage);
    assert_no_overlaps(&surface, &tiling, 0.01);
}

#[test]
fn tiles_on_a_ragged_quad_mesh_are_cut_to_the_surface() {
    // A shell of edge 0.1 quads turned 30 degrees against the square surface: a staircase
    // boundary that falls short of the surface's edge by up to one and a half quads, as
    // QuadriFlow's does.
    let surface = hypar_with_opening();
    let (cos, sin) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let (p, f) = lattice([-1.5, 1.5], [-1.5, 1.5], [30, 30], |_, _| 0.0);
    let turned: Vec<Point3<f64>> = p
        .iter()
        .map(|q| {
            let (x, y) = (cos * q.x - sin * q.y, sin * q.x + cos * q.y);
            Point3::new(x, y, 0.3 * x * y)
        })
        .collect();
    let quads = keep_faces(turned, f, |c| c.x.abs() < 0.93 && c.y.abs() < 0.93);
    let spec = SMALL;
    let finish = FinishOptions::for_spec(&spec);
    // Every pair of neighbouring quads becomes a tile in one of these patterns: greedy
    // rounds over the mesh's interior edges.
    let topology = Topology::new(&quads).unwrap();
    let mut candidates: Vec<[usize; 2]> = topology
        .edges()
        .iter()
        .filter_map(|e| match e.faces[..] {
            [a, b] => Some([a, b]),
            _ => None,
        })
        .collect();
    while !candidates.is_empty() {
        let mut used = vec![false; quads.face_count()];
        let mut pairs = Vec::new();
        candidates.retain(|&[a, b]| {
            let free = !used[a] && !used[b];
            if free {
                (used[a], used[b]) = (true, true);
                pairs.push([a, b]);
            }
            !free
        });
        let tiling = pipeline::tiles_for_pattern(
            &quads,
            Some(&surface),
            pattern_of(&quads, &pairs),
            &spec,
            &finish,
        )
        .unwrap();
        assert!(
            tiling.report.boundary_tiles >= 20,
            "{}",
            tiling.report.boundary_tiles
        );
        check_fabrication(&surface, &tiling, 0.002);
        // Filler pieces close the strip between the staircase and the surface's edge (without
        // them the tiles cover 0.87 of it); what is left are slivers and corners where the
        // continued lattice meets the edge at an angle, and the wide ends of wedge-shaped
        // joints (0.969 since a narrow joint costs the fit twice a wide one, 0.984 before).
        let cutting = tiling.report.cutting.as_ref().unwrap();
        assert!(cutting.filler_tiles > 20, "{}", cutting.filler_tiles);
        assert!(cutting.coverage >= 0.965, "coverage {}", cutting.coverage);
        assert_no_overlaps(&surface, &tiling, 0.01);
    }
}

#[test]
fn equal_cuts_share_a_label_and_mirrored_cuts_too() {
    // Four tiles in a row across a straight edge: the same cut, two of them mirrored.
    let (p, f) = lattice([-1.0, 1.6], [-1.0, 5.0], [13, 30], |_, _| 0.0);
    let surface = PolyMesh::new(p, f).unwrap();
    let quads = generate::grid(2, 4);
    let found = pattern_of(&quads, &[[0, 1], [2, 3], [5, 4], [7, 6]]);
    let finish = {
        let mut o = FinishOptions::for_spec(&SQUARE);
        o.min_kept_width = 0.05;
        o
    };
    let tiling =
        pipeline::tiles_for_pattern(&quads, Some(&surface), found, &SQUARE, &finish).unwrap();
    let cut: Vec<&Tile> = on_quads(&tiling)
        .into_iter()
        .filter(|t| t.kind == TileKind::Boundary)
        .collect();
    assert_eq!(cut.len(), 4);
    assert!(
        cut.iter().all(|t| t.label == cut[0].label),
        "{:?}",
        cut.iter().map(|t| &t.label).collect::<Vec<_>>()
    );
    let group = tiling
        .cut_list
        .iter()
        .find(|g| g.label == cut[0].label)
        .unwrap();
    assert!(group.count >= 4);
}

#[test]
fn the_fabrication_output_is_deterministic() {
    let surface = hypar_with_opening();
    let quads = hypar_quads();
    let spec = SMALL;
    let run = || {
        let found = pattern::solve(&quads, &{
            let mut o = PatternOptions::default();
            o.time_limit = Duration::ZERO;
            o
        })
        .unwrap();
        let tiling = pipeline::tiles_for_pattern(
            &quads,
            Some(&surface),
            found,
            &spec,
            &FinishOptions::for_spec(&spec),
        )
        .unwrap();
        (
            serde_json::to_string(&tiling.tiles).unwrap(),
            serde_json::to_string(&tiling.cut_list).unwrap(),
        )
    };
    assert_eq!(run(), run());
}
