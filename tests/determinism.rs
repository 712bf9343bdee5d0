//! Determinism.
//!
//! - The same input twice gives byte-identical output: pattern JSON, report JSON (both
//!   without their `seconds`), tiles JSON and tiles OBJ; the whole pipeline from a triangle
//!   surface (remesh included) gives byte-identical quads too.
//! - The same mesh with its vertices listed in another order gives exactly the same pairs
//!   and the same tiles (face numbers are unchanged).
//! - The same mesh with its faces (and vertices) listed in another order reaches the same
//!   proven optimum: same status, objective, bound and counts (pairs, half tiles, and the
//!   continuous joints or shifted pairs the objective counts), and its pairs mapped back are a
//!   valid matching of the original.
//!   The pairs themselves may differ where several patterns are optimal (they do on most
//!   of these grids: ties are broken by face order).
//!
//! All of this holds for solves that finish within their time limit; a solve cut short by the
//! limit returns what was found by then, which depends on the machine's speed.

use std::time::Duration;

use tilepattern::control::Control;
use tilepattern::mesh::{PolyMesh, generate, obj};
use tilepattern::pattern::{self, Bond, Pattern, PatternOptions, SolveStatus};
use tilepattern::pipeline::{self, Tiling};
use tilepattern::remesh::RemeshOptions;
use tilepattern::tiles::{FinishOptions, TileSpec};

const SPEC: TileSpec = TileSpec {
    length: 1.9,
    width: 0.95,
    thickness: 0.1,
    joint: 0.1,
};

/// A fixed shuffle of 0..n (a multiplicative step coprime to n).
fn shuffle(n: usize) -> Vec<usize> {
    let step = (1..n)
        .rev()
        .find(|s| gcd(*s, n) == 1 && *s > n / 3)
        .unwrap_or(1);
    (0..n).map(|i| (i * step + 7) % n).collect()
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// `mesh` with faces listed in the order `faces` and vertices in the order `vertices`
/// (new index k holds old index order[k]).
fn permuted(mesh: &PolyMesh, faces: &[usize], vertices: &[usize]) -> PolyMesh {
    let mut new_index = vec![0; vertices.len()];
    vertices
        .iter()
        .enumerate()
        .for_each(|(k, &old)| new_index[old] = k);
    let positions = vertices.iter().map(|&old| mesh.positions()[old]).collect();
    let polygons = faces
        .iter()
        .map(|&f| mesh.faces()[f].iter().map(|&v| new_index[v]).collect())
        .collect();
    PolyMesh::new(positions, polygons).unwrap()
}

fn options(bond: Bond) -> PatternOptions {
    let mut o = PatternOptions::default();
    o.bond = bond;
    o.time_limit = Duration::from_secs(20);
    o
}

/// Everything a run writes, as text, with the wall-clock seconds zeroed.
fn outputs(tiling: &Tiling) -> [String; 4] {
    let mut pattern = serde_json::to_value(&tiling.pattern).unwrap();
    pattern["seconds"] = 0.into();
    let mut report = serde_json::to_value(&tiling.report).unwrap();
    report["seconds"] = serde_json::Value::Null;
    report["pattern"]["seconds"] = serde_json::Value::Null;
    [
        pattern.to_string(),
        report.to_string(),
        serde_json::to_string(&tiling.tiles).unwrap(),
        tilepattern::tiles::to_obj(&tiling.tiles),
    ]
}

/// Meshes, bonds and tiles the permutation tests run on: all solve to a proven optimum fast.
fn cases() -> [(PolyMesh, Bond, TileSpec); 6] {
    let shell_tile = TileSpec {
        length: 0.58,
        width: 0.29,
        thickness: 0.015,
        joint: 0.02,
    };
    [
        (generate::grid(8, 7), Bond::Staggered { weight: 0.5 }, SPEC),
        (generate::grid(6, 6), Bond::Stack, SPEC),
        (
            generate::grid(7, 5),
            Bond::RunningBond { weight: 0.5 },
            SPEC,
        ),
        (
            generate::corner_supported_shell(2.0, 0.3),
            Bond::Staggered { weight: 0.5 },
            shell_tile,
        ),
        (
            generate::grid(6, 6),
            Bond::Herringbone { weight: 0.4 },
            SPEC,
        ),
        (
            generate::grid(6, 5),
            Bond::BasketWeave { weight: 0.4 },
            SPEC,
        ),
    ]
}

fn tiling(mesh: &PolyMesh, found: Pattern, spec: &TileSpec) -> Tiling {
    pipeline::tiles_for_pattern(mesh, None, found, spec, &FinishOptions::for_spec(spec)).unwrap()
}

#[test]
fn the_same_input_gives_byte_identical_output() {
    let shell = generate::corner_supported_shell(2.0, 0.145);
    let spec = TileSpec {
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
    };
    for bond in [Bond::Stack, Bond::Staggered { weight: 0.5 }] {
        let run = || {
            let found = pattern::solve(&shell, &options(bond)).unwrap();
            assert_eq!(
                found.status,
                SolveStatus::Optimal,
                "{bond:?}: a solve cut short may differ"
            );
            outputs(&tiling(&shell, found, &spec))
        };
        assert_eq!(run(), run(), "{bond:?}");
    }
}

#[test]
fn the_whole_pipeline_is_deterministic_from_a_triangle_surface() {
    let spec = TileSpec {
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
    };
    let surface = generate::triangulate_quads(&generate::corner_supported_shell(
        1.2,
        spec.target_edge() / 3.0,
    ));
    let remesh = {
        let mut o = RemeshOptions::default();
        o.target_edge = spec.target_edge();
        o
    };
    let run = || {
        let (remeshed, tiling) = pipeline::tile_surface(
            &surface,
            &remesh,
            &options(Bond::Staggered { weight: 0.5 }),
            &spec,
            &FinishOptions::for_spec(&spec),
            &mut Control::none(),
        )
        .unwrap();
        assert_eq!(tiling.pattern.status, SolveStatus::Optimal);
        (obj::to_string(&remeshed.quads), outputs(&tiling))
    };
    assert_eq!(run(), run());
}

#[test]
fn permuted_vertices_give_the_same_pairs_and_tiles() {
    // The herringbone's two mirror images and the basket weave's two colourings tie on a
    // grid, and which one CBC returns follows the order of its columns, which the edges'
    // vertex numbers give: their optima are compared in
    // `permuted_faces_and_vertices_give_the_same_optimum` instead.
    let cases = cases().into_iter().filter(|(_, bond, _)| {
        !matches!(bond, Bond::Herringbone { .. } | Bond::BasketWeave { .. })
    });
    for (mesh, bond, spec) in cases {
        let same_faces: Vec<usize> = (0..mesh.face_count()).collect();
        let shuffled = permuted(&mesh, &same_faces, &shuffle(mesh.positions().len()));
        let a = pattern::solve(&mesh, &options(bond)).unwrap();
        let b = pattern::solve(&shuffled, &options(bond)).unwrap();
        assert_eq!(a.status, SolveStatus::Optimal, "{bond:?}");
        assert_eq!(
            (&a.pairs, &a.unpaired, a.objective),
            (&b.pairs, &b.unpaired, b.objective),
            "{bond:?}"
        );
        let (x, y) = (
            outputs(&tiling(&mesh, a, &spec)),
            outputs(&tiling(&shuffled, b, &spec)),
        );
        assert_eq!(x[3], y[3], "{bond:?}: tiles OBJ");
        assert_eq!(x[1], y[1], "{bond:?}: report");
    }
}

#[test]
fn permuted_faces_and_vertices_give_the_same_optimum() {
    for (mesh, bond, spec) in cases() {
        let faces = shuffle(mesh.face_count());
        let vertices = shuffle(mesh.positions().len());
        let shuffled = permuted(&mesh, &faces, &vertices);
        let a = pattern::solve(&mesh, &options(bond)).unwrap();
        let b = pattern::solve(&shuffled, &options(bond)).unwrap();
        assert_eq!(
            (a.status, b.status),
            (SolveStatus::Optimal, SolveStatus::Optimal),
            "{bond:?}"
        );
        // The bond's own count follows from the objective; the other one is free to differ.
        let numbers = |p: &Pattern| {
            let term = match bond {
                Bond::Stack => 0,
                Bond::Staggered { .. } => p.continuous_joints,
                Bond::RunningBond { .. } => p.shifted_pairs,
                Bond::Herringbone { .. } | Bond::BasketWeave { .. } => p.bond_pairs,
                other => panic!("no count for {other:?}"),
            };
            (p.objective, p.bound, p.pairs.len(), p.unpaired.len(), term)
        };
        assert_eq!(numbers(&a), numbers(&b), "{bond:?}");
        // Relabelled back, the shuffled mesh's pairs are a valid matching of the original.
        let mut used = vec![false; mesh.face_count()];
        for &[x, y] in &b.pairs {
            let (f, g) = (faces[x], faces[y]);
            assert!(!used[f] && !used[g]);
            (used[f], used[g]) = (true, true);
            assert!(
                mesh.faces()[f]
                    .iter()
                    .filter(|v| mesh.faces()[g].contains(v))
                    .count()
                    == 2,
                "faces {f} and {g} share an edge"
            );
        }
        // Tiles built on either list the same kinds.
        let count = |m: &PolyMesh, p| {
            let t = tiling(m, p, &spec);
            (t.report.full_tiles, t.report.half_tiles)
        };
        assert_eq!(count(&mesh, a), count(&shuffled, b), "{bond:?}");
    }
}
