//! Determinism: the same input gives the same output, and the same mesh with its faces and
//! vertices listed in another order gives the same result up to relabelling (proven optima
//! agree; the patterns themselves may differ where several are optimal).

use std::time::Duration;

use tilepattern::mesh::{PolyMesh, generate};
use tilepattern::pattern::{self, Bond, PatternOptions, SolveStatus};
use tilepattern::pipeline;
use tilepattern::tiles::{FinishOptions, TileSpec};

const SPEC: TileSpec = TileSpec { length: 1.9, width: 0.95, thickness: 0.1, joint: 0.1 };

/// A fixed shuffle of 0..n (a multiplicative step coprime to n).
fn shuffle(n: usize) -> Vec<usize> {
    let step = (1..n).rev().find(|s| gcd(*s, n) == 1 && *s > n / 3).unwrap_or(1);
    (0..n).map(|i| (i * step + 7) % n).collect()
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// `mesh` with faces listed in the order `faces` and vertices in the order `vertices`
/// (new index k holds old index order[k]).
fn permuted(mesh: &PolyMesh, faces: &[usize], vertices: &[usize]) -> PolyMesh {
    let mut new_index = vec![0; vertices.len()];
    vertices.iter().enumerate().for_each(|(k, &old)| new_index[old] = k);
    let positions = vertices.iter().map(|&old| mesh.positions()[old]).collect();
    let polygons = faces.iter().map(|&f| mesh.faces()[f].iter().map(|&v| new_index[v]).collect()).collect();
    PolyMesh::new(positions, polygons).unwrap()
}

fn options(bond: Bond) -> PatternOptions {
    PatternOptions { bond, time_limit: Duration::from_secs(20), ..PatternOptions::default() }
}

#[test]
fn the_same_input_gives_byte_identical_output() {
    let shell = generate::corner_supported_shell(2.0, 0.145);
    let spec = TileSpec { length: 0.28, width: 0.14, thickness: 0.015, joint: 0.01 };
    let run = || {
        let tiling = pipeline::tiles_for_pattern(
            &shell,
            None,
            pattern::solve(&shell, &options(Bond::Staggered { weight: 0.5 })).unwrap(),
            &spec,
            &FinishOptions::for_spec(&spec),
        )
        .unwrap();
        let mut pattern = serde_json::to_value(&tiling.pattern).unwrap();
        pattern["seconds"] = 0.into();
        (pattern.to_string(), serde_json::to_string(&tiling.tiles).unwrap(), tilepattern::tiles::to_obj(&tiling.tiles))
    };
    assert_eq!(run(), run());
}

#[test]
fn permuted_faces_and_vertices_give_the_same_optimum() {
    for (mesh, bond) in [
        (generate::grid(8, 7), Bond::Staggered { weight: 0.5 }),
        (generate::grid(6, 6), Bond::Stack),
        (generate::grid(7, 5), Bond::RunningBond { weight: 0.5 }),
    ] {
        let faces = shuffle(mesh.face_count());
        let vertices = shuffle(mesh.positions().len());
        let shuffled = permuted(&mesh, &faces, &vertices);
        let a = pattern::solve(&mesh, &options(bond)).unwrap();
        let b = pattern::solve(&shuffled, &options(bond)).unwrap();
        assert_eq!((a.status, b.status), (SolveStatus::Optimal, SolveStatus::Optimal), "{bond:?}");
        assert_eq!(a.objective, b.objective, "{bond:?}");
        // Relabelled back, the shuffled mesh's pairs are a valid matching of the original.
        let mut used = vec![false; mesh.face_count()];
        for &[x, y] in &b.pairs {
            let (f, g) = (faces[x], faces[y]);
            assert!(!used[f] && !used[g]);
            (used[f], used[g]) = (true, true);
            assert!(mesh.faces()[f].iter().filter(|v| mesh.faces()[g].contains(v)).count() == 2, "faces {f} and {g} share an edge");
        }
        // Tiles built on either list the same kinds.
        let count = |m: &PolyMesh, p| {
            let t = pipeline::tiles_for_pattern(m, None, p, &SPEC, &FinishOptions::for_spec(&SPEC)).unwrap();
            (t.report.full_tiles, t.report.half_tiles)
        };
        assert_eq!(count(&mesh, a), count(&shuffled, b));
    }
}
