//! The bad-input table: every kind of bad input, at every entry point of the Rust API and the
//! command line, gets a specific error naming the problem and where (or a documented graceful
//! result). The C ABI's rows are in `tests/c/test_bad_input.c`.

use std::process::Command;
use std::time::Duration;

use nalgebra::Point3;
use tilepattern::mesh::{self, MeshError, PolyMesh, generate};
use tilepattern::pattern::{self, Bond, PatternError, PatternOptions};
use tilepattern::remesh::{self, RemeshError, RemeshOptions};
use tilepattern::tiles::{self, TileError, TileSpec};

fn points(xyz: &[[f64; 3]]) -> Vec<Point3<f64>> {
    xyz.iter().map(|p| Point3::from(*p)).collect()
}

/// A unit square split into two triangles plus one more vertex, for building bad faces.
const SQUARE: [[f64; 3]; 5] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [2.0, 0.0, 0.0]];

/// Rows: (what, vertices, faces, the error expected and the words its message must hold).
#[test]
fn bad_meshes_are_refused_with_the_culprit_named() {
    let nan = [[0.0, 0.0, 0.0], [1.0, 0.0, f64::NAN], [1.0, 1.0, 0.0]];
    let inf = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, f64::INFINITY, 0.0]];
    type Row = (&'static str, Vec<[f64; 3]>, Vec<Vec<usize>>, fn(&MeshError) -> bool, &'static str);
    let rows: Vec<Row> = vec![
        ("NaN coordinate", nan.to_vec(), vec![vec![0, 1, 2]], |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 1 }), "vertex 1"),
        ("infinite coordinate", inf.to_vec(), vec![vec![0, 1, 2]], |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 2 }), "vertex 2"),
        ("index out of range", SQUARE.to_vec(), vec![vec![0, 1, 9]], |e| matches!(e, MeshError::IndexOutOfRange { face: 0, index: 9, .. }), "vertex 9"),
        ("repeated vertex", SQUARE.to_vec(), vec![vec![0, 1, 2], vec![0, 2, 2, 3]], |e| matches!(e, MeshError::RepeatedIndex { face: 1, vertex: 2 }), "face 1"),
        ("two-vertex face", SQUARE.to_vec(), vec![vec![0, 1]], |e| matches!(e, MeshError::TooFewVertices { face: 0, count: 2 }), "at least 3"),
        ("duplicate face", SQUARE.to_vec(), vec![vec![0, 1, 2, 3], vec![1, 2, 3, 0]], |e| matches!(e, MeshError::DuplicateFace { face: 1, first: 0 }), "repeats face 0"),
        (
            "non-manifold edge",
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.5, 1.0, 0.0], [0.5, -1.0, 0.0], [0.5, 0.0, 1.0]],
            vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]],
            |e| matches!(e, MeshError::NonManifoldEdge { a: 0, b: 1, face_count: 3, .. }),
            "edge 0-1",
        ),
        (
            "inconsistent orientation",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2], vec![0, 2, 3], vec![1, 2, 4]],
            |e| matches!(e, MeshError::InconsistentOrientation { a: 1, b: 2, faces: [0, 2] }),
            "orientations disagree",
        ),
        ("empty mesh", Vec::new(), Vec::new(), |e| matches!(e, MeshError::Empty { .. }), "empty"),
        ("no faces", SQUARE.to_vec(), Vec::new(), |e| matches!(e, MeshError::Empty { faces: 0, .. }), "at least one face"),
    ];
    for (what, vertices, faces, expected, words) in rows {
        let error = PolyMesh::new(points(&vertices), faces).expect_err(what);
        assert!(expected(&error), "{what}: got {error:?}");
        assert!(error.to_string().contains(words), "{what}: message {error}");
    }
}

#[test]
fn inconsistent_orientation_names_the_edge_between_two_quads() {
    let mut faces: Vec<Vec<usize>> = generate::grid(2, 1).faces().to_vec();
    faces[1].reverse();
    let error = PolyMesh::new(generate::grid(2, 1).positions().to_vec(), faces).unwrap_err();
    assert!(matches!(error, MeshError::InconsistentOrientation { faces: [0, 1], .. }), "{error:?}");
}

#[test]
fn sizes_over_the_limits_are_refused_before_allocating() {
    assert!(matches!(mesh::check_size(mesh::MAX_VERTICES + 1, 1, 3), Err(MeshError::TooLarge { what: "vertices", .. })));
    assert!(matches!(mesh::check_size(3, mesh::MAX_FACES + 1, 3), Err(MeshError::TooLarge { what: "faces", .. })));
    assert!(matches!(mesh::check_size(3, 1, usize::MAX), Err(MeshError::TooLarge { what: "face indices", .. })));
    assert!(mesh::check_size(3, 1, 3).is_ok());
}

/// Graceful rows: inputs that are odd but meaningful get a documented result.
#[test]
fn odd_but_valid_meshes_give_documented_results() {
    let spec = TileSpec { length: 1.9, width: 0.95, thickness: 0.1, joint: 0.1 };
    let quick = PatternOptions { time_limit: Duration::from_secs(2), ..PatternOptions::default() };

    // A zero-area quad (three corners at one point, as remeshers leave them): accepted; its
    // tile has a finite frame.
    let mut positions = generate::grid(2, 1).positions().to_vec();
    positions[2] = positions[1];
    positions[5] = positions[1];
    let degenerate = PolyMesh::new(positions, generate::grid(2, 1).faces().to_vec()).unwrap();
    let found = pattern::solve(&degenerate, &quick).unwrap();
    let built = tiles::build(&degenerate, &found, &TileSpec { length: 0.5, ..spec }).unwrap();
    assert!(built.iter().all(|t| t.corners.iter().flatten().all(|c| c.is_finite())));

    // Two quads touching at one vertex only (a non-manifold vertex): accepted, each a half
    // tile.
    let bowtie = PolyMesh::new(
        points(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [2.0, 1.0, 0.0], [2.0, 2.0, 0.0], [1.0, 2.0, 0.0]]),
        vec![vec![0, 1, 2, 3], vec![2, 4, 5, 6]],
    )
    .unwrap();
    let found = pattern::solve(&bowtie, &quick).unwrap();
    assert_eq!((found.pairs.len(), found.unpaired.len()), (0, 2));

    // Disconnected pieces: each is matched on its own.
    let grid = generate::grid(2, 1);
    let mut positions = grid.positions().to_vec();
    positions.extend(grid.positions().iter().map(|p| p + nalgebra::Vector3::new(10.0, 0.0, 0.0)));
    let mut faces = grid.faces().to_vec();
    faces.extend(grid.faces().iter().map(|f| f.iter().map(|v| v + 6).collect()));
    let pieces = PolyMesh::new(positions, faces).unwrap();
    assert_eq!(pattern::solve(&pieces, &quick).unwrap().pairs.len(), 2);

    // A single quad: one half tile.
    let single = generate::grid(1, 1);
    let found = pattern::solve(&single, &quick).unwrap();
    assert_eq!(found.unpaired, vec![0]);
    assert_eq!(tiles::build(&single, &found, &TileSpec { length: 1.0, width: 0.5, ..spec }).unwrap().len(), 1);

    // Only triangles: nothing to pair; every face is reported as not a quad.
    let triangles = generate::triangulate_quads(&generate::grid(3, 3));
    let found = pattern::solve(&triangles, &quick).unwrap();
    assert_eq!((found.pairs.len(), found.non_quad.len()), (0, 18));
    assert!(tiles::build(&triangles, &found, &spec).unwrap().is_empty());
}

#[test]
fn bad_pattern_options_are_refused() {
    let grid = generate::grid(4, 4);
    for weight in [f64::NAN, -1.0, f64::INFINITY] {
        let options = PatternOptions { bond: Bond::Staggered { weight }, ..PatternOptions::default() };
        assert!(matches!(pattern::solve(&grid, &options), Err(PatternError::InvalidWeight { .. })), "weight {weight}");
    }
    for seconds in [-1.0, f64::NAN, 1e300] {
        assert!(matches!(PatternOptions::time_limit_from_secs(seconds), Err(PatternError::InvalidTimeLimit { .. })), "{seconds} s");
    }
    let forced = |pairs: Vec<[usize; 2]>, excluded: Vec<usize>| PatternOptions { forced_pairs: pairs, excluded_faces: excluded, ..PatternOptions::default() };
    assert!(matches!(pattern::solve(&grid, &forced(vec![[0, 99]], vec![])), Err(PatternError::FaceOutOfRange { face: 99, .. })));
    assert!(matches!(pattern::solve(&grid, &forced(vec![[0, 5]], vec![])), Err(PatternError::ForcedNotAdjacent { a: 0, b: 5 })));
    assert!(matches!(pattern::solve(&grid, &forced(vec![[0, 1], [1, 2]], vec![])), Err(PatternError::ForcedTwice { face: 1 })));
    assert!(matches!(pattern::solve(&grid, &forced(vec![[0, 1]], vec![1])), Err(PatternError::ForcedExcluded { face: 1 })));
    assert!(matches!(pattern::solve(&grid, &forced(vec![], vec![16])), Err(PatternError::FaceOutOfRange { face: 16, .. })));
    // Time limit 0: the best start, not proven unless it meets the bound.
    let zero = PatternOptions { time_limit: Duration::ZERO, ..PatternOptions::default() };
    let found = pattern::solve(&grid, &zero).unwrap();
    assert!(found.bound >= found.objective);
}

#[test]
fn bad_tile_sizes_are_refused() {
    let grid = generate::grid(4, 4);
    let found = pattern::solve(&grid, &PatternOptions { time_limit: Duration::ZERO, ..PatternOptions::default() }).unwrap();
    let ok = TileSpec { length: 1.9, width: 0.95, thickness: 0.1, joint: 0.1 };
    let rows = [
        ("zero length", TileSpec { length: 0.0, ..ok }, "length"),
        ("negative width", TileSpec { width: -1.0, ..ok }, "width"),
        ("NaN thickness", TileSpec { thickness: f64::NAN, ..ok }, "thickness"),
        ("negative joint", TileSpec { joint: -0.1, ..ok }, "joint"),
    ];
    for (what, spec, name) in rows {
        let error = tiles::build(&grid, &found, &spec).expect_err(what);
        assert!(matches!(error, TileError::InvalidSpec { .. }) && error.to_string().contains(name), "{what}: {error}");
    }
    let huge = tiles::build(&grid, &found, &TileSpec { length: 100.0, ..ok }).unwrap_err();
    assert!(matches!(huge, TileError::TileLargerThanMesh { .. }), "{huge:?}");
    let mut wrong = found.clone();
    wrong.pairs.push([0, 15]);
    assert!(tiles::build(&grid, &wrong, &ok).is_err(), "a pair from another mesh");
}

#[test]
fn bad_remesh_options_are_refused() {
    let surface = generate::triangulate_quads(&generate::grid(6, 6));
    for edge in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let options = RemeshOptions { target_edge: edge, ..RemeshOptions::default() };
        assert!(matches!(remesh::remesh(&surface, &options), Err(RemeshError::BadTargetEdge(_))), "edge {edge}");
    }
    let huge = RemeshOptions { target_edge: 100.0, ..RemeshOptions::default() };
    assert!(matches!(remesh::remesh(&surface, &huge), Err(RemeshError::TargetEdgeTooLarge { .. })));
    let tiny = RemeshOptions { target_edge: 1e-5, ..RemeshOptions::default() };
    assert!(matches!(remesh::remesh(&surface, &tiny), Err(RemeshError::TargetEdgeTooSmall { .. })));
}

/// The command line: a non-zero exit and a message naming the problem, never a panic.
#[test]
fn the_command_line_reports_bad_input() {
    let dir = std::env::temp_dir().join(format!("tp-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let nan = write("nan.obj", "v 0 0 0\nv 1 0 nan\nv 1 1 0\nf 1 2 3\n");
    let range = write("range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n");
    let empty = write("empty.obj", "");
    let junk = write("junk.obj", "v 0 0\nf 1 2 3\n");
    let quads = write("quads.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n");
    let rows: Vec<(Vec<&str>, &str)> = vec![
        (vec!["match", &nan], "vertex 1"),
        (vec!["match", &range], "vertex 6"),
        (vec!["match", &empty], "empty"),
        (vec!["match", &junk], "line 1"),
        (vec!["match", "/nonexistent/x.obj"], "x.obj"),
        (vec!["match", &quads, "--weight", "nan"], "weight"),
        (vec!["match", &quads, "--time-limit=-1"], "time limit"),
        (vec!["match", &quads, "--force", "0,7"], "face 7"),
        (vec!["remesh", &quads, "--edge", "0", "-o", "/dev/null"], "target edge"),
        (vec!["demo", "--span", "0", "--out", "/tmp/tp-bad-demo"], "span"),
    ];
    for (args, words) in rows {
        let out = Command::new(env!("CARGO_BIN_EXE_tilepattern")).args(&args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert_eq!(out.status.code(), Some(1), "{args:?}: {stderr}");
        assert!(stderr.contains(words), "{args:?}: stderr {stderr}");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
}
