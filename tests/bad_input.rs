//! The bad-input table: every kind of bad input, at every entry point of the Rust API and the
//! command line, gets a specific error naming the problem and where (the face, vertex, edge,
//! OBJ line or option), or a documented graceful result that the row checks. The C ABI's
//! rows are in `tests/c/test_bad_input.c`.
//!
//! Decisions recorded here:
//! - OBJ negative indices are legal OBJ (relative to the last vertex read) and are accepted;
//!   one reaching before the first vertex, and index 0, are syntax errors naming the line.
//! - Zero-area faces, vertices where pieces touch, disconnected pieces, unused vertices,
//!   single faces and triangle-only meshes are accepted (remeshers and designers make them);
//!   faces that are not quads are never paired and are listed in `non_quad`.
//! - Time limits: NaN, negative and infinite are refused; 0 returns the best start at once;
//!   finite limits above `pattern::MAX_TIME_LIMIT_SECONDS` count as that limit.
//! - The command line exits with 2 for arguments it cannot parse (clap) and 1 for input and
//!   option values the library refuses; never with a panic.

use std::process::Command;
use std::time::Duration;

use nalgebra::{Point3, Vector3};
use tilepattern::mesh::{self, MeshError, PolyMesh, generate, obj};
use tilepattern::pattern::{self, Bond, Pattern, PatternError, PatternOptions};
use tilepattern::pipeline::{self, Error};
use tilepattern::remesh::{self, FieldDirection, RemeshError, RemeshOptions};
use tilepattern::tiles::{self, FinishOptions, TileError, TileSpec};

fn points(xyz: &[[f64; 3]]) -> Vec<Point3<f64>> {
    xyz.iter().map(|p| Point3::from(*p)).collect()
}

/// Asserts that `result` failed with an error `expected` accepts whose message holds every
/// one of `words`.
#[track_caller]
fn refused<T: std::fmt::Debug, E: std::fmt::Debug + std::fmt::Display>(
    what: &str,
    result: Result<T, E>,
    expected: impl Fn(&E) -> bool,
    words: &[&str],
) {
    let error = result.expect_err(what);
    assert!(expected(&error), "{what}: got {error:?}");
    let message = error.to_string();
    for word in words {
        assert!(
            message.contains(word),
            "{what}: message \"{message}\" lacks \"{word}\""
        );
    }
}

/// A unit square and two more vertices, for building bad faces: 0-3 the square
/// counter-clockwise, 4 = (2, 0), 5 = (2, 1).
const SQUARE: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
    [2.0, 0.0, 0.0],
    [2.0, 1.0, 0.0],
];

/// A tile for unit quads (two faces of edge 1 with a joint of 0.1).
const UNIT_TILE: TileSpec = TileSpec {
    length: 1.9,
    width: 0.95,
    thickness: 0.1,
    joint: 0.1,
};

fn quick() -> PatternOptions {
    let mut o = PatternOptions::default();
    o.time_limit = Duration::from_secs(5);
    o
}

/// Rows: (what, vertices, faces, the error expected, the words its message must hold).
#[test]
fn bad_meshes_are_refused_with_the_culprit_named() {
    let with = |k: usize, value: [f64; 3]| {
        let mut v = SQUARE.to_vec();
        v[k] = value;
        v
    };
    type Row = (
        &'static str,
        Vec<[f64; 3]>,
        Vec<Vec<usize>>,
        fn(&MeshError) -> bool,
        &'static [&'static str],
    );
    let rows: Vec<Row> = vec![
        (
            "NaN coordinate",
            with(1, [1.0, 0.0, f64::NAN]),
            vec![vec![0, 1, 2]],
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 1 }),
            &["vertex 1", "NaN"],
        ),
        (
            "+inf coordinate",
            with(2, [1.0, f64::INFINITY, 0.0]),
            vec![vec![0, 1, 2]],
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 2 }),
            &["vertex 2"],
        ),
        (
            "-inf coordinate",
            with(0, [f64::NEG_INFINITY, 0.0, 0.0]),
            vec![vec![0, 1, 2]],
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 0 }),
            &["vertex 0"],
        ),
        (
            "NaN in an unused vertex",
            with(5, [f64::NAN; 3]),
            vec![vec![0, 1, 2]],
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 5 }),
            &["vertex 5"],
        ),
        (
            "coordinate beyond MAX_COORDINATE",
            with(3, [0.0, -2e12, 0.0]),
            vec![vec![0, 1, 2, 3]],
            |e| matches!(e, MeshError::CoordinateTooLarge { vertex: 3, .. }),
            &["vertex 3", "at most 1e12"],
        ),
        (
            "index out of range",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2], vec![0, 2, 9]],
            |e| {
                matches!(
                    e,
                    MeshError::IndexOutOfRange {
                        face: 1,
                        index: 9,
                        vertex_count: 6
                    }
                )
            },
            &["face 1", "vertex 9", "6 vertices"],
        ),
        (
            "negative index (as a caller's -1 cast to usize)",
            SQUARE.to_vec(),
            vec![vec![0, 1, usize::MAX]],
            |e| {
                matches!(
                    e,
                    MeshError::IndexOutOfRange {
                        face: 0,
                        index: usize::MAX,
                        ..
                    }
                )
            },
            &["face 0", "18446744073709551615"],
        ),
        (
            "repeated vertex in a face",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2], vec![0, 2, 2, 3]],
            |e| matches!(e, MeshError::RepeatedIndex { face: 1, vertex: 2 }),
            &["face 1", "vertex 2", "more than once"],
        ),
        (
            "repeated vertex, not adjacent",
            SQUARE.to_vec(),
            vec![vec![0, 1, 0, 2]],
            |e| matches!(e, MeshError::RepeatedIndex { face: 0, vertex: 0 }),
            &["face 0"],
        ),
        (
            "face with no vertex",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2], vec![]],
            |e| matches!(e, MeshError::TooFewVertices { face: 1, count: 0 }),
            &["face 1", "at least 3"],
        ),
        (
            "one-vertex face",
            SQUARE.to_vec(),
            vec![vec![4]],
            |e| matches!(e, MeshError::TooFewVertices { face: 0, count: 1 }),
            &["face 0"],
        ),
        (
            "two-vertex face",
            SQUARE.to_vec(),
            vec![vec![0, 1]],
            |e| matches!(e, MeshError::TooFewVertices { face: 0, count: 2 }),
            &["face 0", "2 vertices"],
        ),
        (
            "duplicate face",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2, 3], vec![0, 1, 2, 3]],
            |e| matches!(e, MeshError::DuplicateFace { face: 1, first: 0 }),
            &["face 1", "repeats face 0"],
        ),
        (
            "duplicate face, rotated",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2, 3], vec![1, 4, 5, 2], vec![2, 3, 0, 1]],
            |e| matches!(e, MeshError::DuplicateFace { face: 2, first: 0 }),
            &["face 2", "repeats face 0"],
        ),
        (
            "duplicate face, reversed",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2, 3], vec![3, 2, 1, 0]],
            |e| matches!(e, MeshError::DuplicateFace { face: 1, first: 0 }),
            &["face 1"],
        ),
        (
            "non-manifold edge (3 faces)",
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [0.5, -1.0, 0.0],
                [0.5, 0.0, 1.0],
            ],
            vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]],
            |e| {
                matches!(
                    e,
                    MeshError::NonManifoldEdge {
                        a: 0,
                        b: 1,
                        face_count: 3,
                        ..
                    }
                )
            },
            &["edge 0-1", "3 faces", "[0, 1, 2]"],
        ),
        (
            // The third face has no area: it is named, not taken for a fin (before: 'a fin,
            // a wall or a second shell').
            "a face without area along an edge",
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.5, 1.0, 0.0],
                [0.5, -1.0, 0.0],
                [0.5, 0.0, 0.0],
            ],
            vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 4, 1]],
            |e| {
                matches!(
                    e,
                    MeshError::DegenerateFace {
                        face: 2,
                        a: 0,
                        b: 1
                    }
                )
            },
            &["face 2 has no area", "CullDegenerateMeshFaces"],
        ),
        (
            "inconsistent orientation (triangles)",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2], vec![0, 2, 3], vec![1, 2, 4]],
            |e| {
                matches!(
                    e,
                    MeshError::InconsistentOrientation {
                        a: 1,
                        b: 2,
                        faces: [0, 2]
                    }
                )
            },
            &[
                "faces [0, 2]",
                "vertex 1 to vertex 2",
                "orientations disagree",
            ],
        ),
        (
            "inconsistent orientation (quads)",
            SQUARE.to_vec(),
            vec![vec![0, 1, 2, 3], vec![1, 2, 5, 4]],
            |e| {
                matches!(
                    e,
                    MeshError::InconsistentOrientation {
                        a: 1,
                        b: 2,
                        faces: [0, 1]
                    }
                )
            },
            &["faces [0, 1]"],
        ),
        (
            "empty mesh",
            Vec::new(),
            Vec::new(),
            |e| {
                matches!(
                    e,
                    MeshError::Empty {
                        vertices: 0,
                        faces: 0
                    }
                )
            },
            &["empty", "0 vertices, 0 faces"],
        ),
        (
            "vertices but no faces",
            SQUARE.to_vec(),
            Vec::new(),
            |e| matches!(e, MeshError::Empty { faces: 0, .. }),
            &["at least one face"],
        ),
        (
            "faces but no vertices",
            Vec::new(),
            vec![vec![0, 1, 2]],
            |e| {
                matches!(
                    e,
                    MeshError::Empty {
                        vertices: 0,
                        faces: 1
                    }
                )
            },
            &["0 vertices"],
        ),
    ];
    for (what, vertices, faces, expected, words) in rows {
        refused(
            what,
            PolyMesh::new(points(&vertices), faces),
            expected,
            words,
        );
    }
    // Right at the coordinate limit is fine.
    PolyMesh::new(
        points(&[[0.0, 0.0, 0.0], [1e12, 0.0, 0.0], [0.0, -1e12, 0.0]]),
        vec![vec![0, 1, 2]],
    )
    .unwrap();
}

#[test]
fn sizes_over_the_limits_are_refused_before_allocating() {
    let over = |what: &'static str| move |e: &MeshError| matches!(e, MeshError::TooLarge { what: w, .. } if *w == what);
    refused(
        "vertices",
        mesh::check_size(mesh::MAX_VERTICES + 1, 1, 3),
        over("vertices"),
        &["4000001 vertices", "at most 4000000"],
    );
    refused(
        "faces",
        mesh::check_size(3, mesh::MAX_FACES + 1, 3),
        over("faces"),
        &["4000001 faces"],
    );
    refused(
        "indices",
        mesh::check_size(3, 1, usize::MAX),
        over("face indices"),
        &["face indices"],
    );
    mesh::check_size(mesh::MAX_VERTICES, mesh::MAX_FACES, mesh::MAX_INDICES).unwrap();
    // PolyMesh::new checks the counts first, before looking at a single coordinate.
    let many = vec![Point3::new(f64::NAN, 0.0, 0.0); mesh::MAX_VERTICES + 1];
    refused(
        "PolyMesh with too many vertices",
        PolyMesh::new(many, vec![vec![0, 1, 2]]),
        over("vertices"),
        &["vertices"],
    );
}

/// OBJ text: syntax errors name the line; what parses is validated as above.
#[test]
fn obj_rows() {
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    type Row = (
        &'static str,
        String,
        fn(&MeshError) -> bool,
        &'static [&'static str],
    );
    let rows: Vec<Row> = vec![
        (
            "index 0",
            format!("{square}f 0 1 2\n"),
            |e| matches!(e, MeshError::ObjSyntax { line: 5, .. }),
            &["line 5", "index 0"],
        ),
        (
            "negative index before the first vertex",
            format!("{square}f -1 -2 -5\n"),
            |e| matches!(e, MeshError::ObjSyntax { line: 5, .. }),
            &["line 5", "-5"],
        ),
        (
            "i64::MIN index",
            format!("{square}f 1 2 -9223372036854775808\n"),
            |e| matches!(e, MeshError::ObjSyntax { line: 5, .. }),
            &["line 5"],
        ),
        (
            "index beyond i64",
            format!("{square}f 1 2 99999999999999999999\n"),
            |e| matches!(e, MeshError::ObjSyntax { line: 5, .. }),
            &["line 5", "not a vertex reference"],
        ),
        (
            "index out of range",
            format!("{square}f 1 2 7\n"),
            |e| {
                matches!(
                    e,
                    MeshError::IndexOutOfRange {
                        face: 0,
                        index: 6,
                        ..
                    }
                )
            },
            &["face 0", "vertex 6"],
        ),
        (
            "huge positive index",
            format!("{square}f 1 2 9223372036854775807\n"),
            |e| matches!(e, MeshError::IndexOutOfRange { face: 0, .. }),
            &["face 0"],
        ),
        (
            "missing coordinate",
            "v 0 0\n".into(),
            |e| matches!(e, MeshError::ObjSyntax { line: 1, .. }),
            &["line 1", "x, y and z"],
        ),
        (
            "coordinate not a number",
            "v 0 zero 0\n".into(),
            |e| matches!(e, MeshError::ObjSyntax { line: 1, .. }),
            &["line 1", "'zero'"],
        ),
        (
            "reference not a number",
            format!("{square}f 1 b 3\n"),
            |e| matches!(e, MeshError::ObjSyntax { line: 5, .. }),
            &["line 5", "'b'"],
        ),
        (
            "nan coordinate",
            format!("{square}v nan 0 0\nf 1 2 5\n"),
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 4 }),
            &["vertex 4"],
        ),
        (
            "overflowing coordinate 1e400",
            format!("{square}v 1e400 0 0\nf 1 2 5\n"),
            |e| matches!(e, MeshError::NonFiniteCoordinate { vertex: 4 }),
            &["vertex 4"],
        ),
        (
            "coordinate 1e13",
            format!("{square}v 1e13 0 0\nf 1 2 5\n"),
            |e| matches!(e, MeshError::CoordinateTooLarge { vertex: 4, .. }),
            &["vertex 4"],
        ),
        (
            "two-vertex face",
            format!("{square}f 1 2\n"),
            |e| matches!(e, MeshError::TooFewVertices { face: 0, count: 2 }),
            &["face 0"],
        ),
        (
            "empty file",
            String::new(),
            |e| matches!(e, MeshError::Empty { .. }),
            &["empty"],
        ),
        (
            "only comments and normals",
            "# nothing\nvn 0 0 1\nvt 0 0\n".into(),
            |e| matches!(e, MeshError::Empty { .. }),
            &["empty"],
        ),
        (
            "duplicate face",
            format!("{square}f 1 2 3 4\nf 2 3 4 1\n"),
            |e| matches!(e, MeshError::DuplicateFace { face: 1, first: 0 }),
            &["face 1"],
        ),
    ];
    for (what, text, expected, words) in rows {
        refused(what, obj::parse(&text), expected, words);
    }

    // Graceful: negative (relative) indices are legal OBJ and mean the same faces as positive
    // ones; texture and normal references are ignored.
    let relative = obj::parse(&format!(
        "{square}f -4 -3 -2 -1\nv 2 0 0\nv 2 1 0\nf 2/7/1 -2//3 -1/1/1 3\n"
    ))
    .unwrap();
    let absolute =
        obj::parse(&format!("{square}f 1 2 3 4\nv 2 0 0\nv 2 1 0\nf 2 5 6 3\n")).unwrap();
    assert_eq!(relative, absolute);

    // More vertices than a mesh may have: refused while reading, before the rest is parsed.
    let too_many = "v 0 0 0\n".repeat(mesh::MAX_VERTICES + 1);
    refused(
        "too many vertices",
        obj::parse(&too_many),
        |e| {
            matches!(
                e,
                MeshError::TooLarge {
                    what: "vertices",
                    ..
                }
            )
        },
        &["4000001 vertices"],
    );
}

/// Graceful rows: inputs that are odd but meaningful get a documented result.
#[test]
fn odd_but_valid_meshes_give_documented_results() {
    let tiles_of = |mesh: &PolyMesh, spec: &TileSpec| {
        let found = pattern::solve(mesh, &quick()).unwrap();
        let tiling =
            pipeline::tiles_for_pattern(mesh, None, found, spec, &FinishOptions::for_spec(spec))
                .unwrap();
        assert!(
            tiling
                .tiles
                .iter()
                .all(|t| t.corners.iter().flatten().all(|c| c.is_finite())),
            "finite corners"
        );
        assert!(
            !serde_json::to_string(&tiling.report)
                .unwrap()
                .contains("null"),
            "no NaN in the report"
        );
        tiling
    };

    // Zero-area faces (three corners at one point, as remeshers leave them; or all four on a
    // line): accepted; their tiles have finite frames.
    let mut positions = generate::grid(2, 1).positions().to_vec();
    positions[2] = positions[1];
    positions[5] = positions[1];
    let degenerate = PolyMesh::new(positions, generate::grid(2, 1).faces().to_vec()).unwrap();
    tiles_of(
        &degenerate,
        &TileSpec {
            length: 0.5,
            ..UNIT_TILE
        },
    );
    let flat_line = PolyMesh::new(
        points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
        ]),
        vec![vec![0, 1, 2, 3]],
    )
    .unwrap();
    assert_eq!(flat_line.area(), 0.0);
    assert_eq!(
        pattern::solve(&flat_line, &quick()).unwrap().unpaired,
        vec![0]
    );

    // Two quads touching at one vertex only (a non-manifold vertex): accepted, each a half
    // tile.
    let bowtie = PolyMesh::new(
        points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
            [2.0, 2.0, 0.0],
            [1.0, 2.0, 0.0],
        ]),
        vec![vec![0, 1, 2, 3], vec![2, 4, 5, 6]],
    )
    .unwrap();
    let found = pattern::solve(&bowtie, &quick()).unwrap();
    assert_eq!((found.pairs.len(), found.unpaired.len()), (0, 2));
    assert_eq!(
        tiles_of(
            &bowtie,
            &TileSpec {
                length: 1.0,
                width: 0.5,
                ..UNIT_TILE
            }
        )
        .report
        .half_tiles,
        2
    );

    // Disconnected pieces: each is matched on its own.
    let grid = generate::grid(2, 1);
    let mut positions = grid.positions().to_vec();
    positions.extend(
        grid.positions()
            .iter()
            .map(|p| p + Vector3::new(10.0, 0.0, 0.0)),
    );
    let mut faces = grid.faces().to_vec();
    faces.extend(
        grid.faces()
            .iter()
            .map(|f| f.iter().map(|v| v + 6).collect()),
    );
    let pieces = PolyMesh::new(positions, faces).unwrap();
    assert_eq!(
        pattern::solve(&pieces, &quick()).unwrap().pairs,
        vec![[0, 1], [2, 3]]
    );
    assert_eq!(tiles_of(&pieces, &UNIT_TILE).report.full_tiles, 2);

    // A single quad: one half tile. A single triangle: no tile, reported as not a quad.
    let single = generate::grid(1, 1);
    let found = pattern::solve(&single, &quick()).unwrap();
    assert_eq!(found.unpaired, vec![0]);
    // (The tile is smaller than its quad: after the fit, filler pieces take the rest.)
    assert_eq!(
        tiles_of(
            &single,
            &TileSpec {
                length: 1.0,
                width: 0.5,
                ..UNIT_TILE
            }
        )
        .report
        .half_tiles,
        1
    );
    let triangle = PolyMesh::new(points(&SQUARE[..3]), vec![vec![0, 1, 2]]).unwrap();
    let found = pattern::solve(&triangle, &quick()).unwrap();
    assert_eq!(
        (
            found.pairs.len(),
            found.unpaired.len(),
            found.non_quad.clone()
        ),
        (0, 0, vec![0])
    );

    // Only triangles: nothing to pair; every face is reported as not a quad, no tile is built.
    let triangles = generate::triangulate_quads(&generate::grid(3, 3));
    let found = pattern::solve(&triangles, &quick()).unwrap();
    assert_eq!(
        (found.pairs.len(), found.non_quad.len(), found.status),
        (0, 18, pattern::SolveStatus::Optimal)
    );
    assert!(
        tiles::build(&triangles, &found, &UNIT_TILE)
            .unwrap()
            .is_empty()
    );

    // Triangles, quads and a pentagon mixed, plus a vertex no face uses: the quads are paired.
    let mixed = PolyMesh::new(
        points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 1.0, 0.0],
            [1.0, 2.0, 0.0],
            [3.0, 0.5, 0.0],
            [9.0, 9.0, 9.0],
        ]),
        vec![
            vec![0, 1, 4, 3],
            vec![1, 2, 5, 4],
            vec![3, 4, 6],
            vec![4, 5, 6],
            vec![2, 7, 5],
        ],
    )
    .unwrap();
    let found = pattern::solve(&mixed, &quick()).unwrap();
    assert_eq!(
        (found.pairs.clone(), found.non_quad.clone()),
        (vec![[0, 1]], vec![2, 3, 4])
    );
    // A closed surface (no boundary at all) is a valid mesh.
    let cube = PolyMesh::new(
        points(&[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ]),
        vec![
            vec![0, 3, 2, 1],
            vec![4, 5, 6, 7],
            vec![0, 1, 5, 4],
            vec![1, 2, 6, 5],
            vec![2, 3, 7, 6],
            vec![3, 0, 4, 7],
        ],
    )
    .unwrap();
    assert_eq!(pattern::solve(&cube, &quick()).unwrap().pairs.len(), 3);
}

/// Huge faces are checked in linear time: one face of a million vertices, and a 20000-gon
/// ringed by quads (listed last, where an edge search in it per neighbour was quadratic).
#[test]
fn huge_faces_are_validated_in_linear_time() {
    let started = std::time::Instant::now();
    let n = 1_000_000;
    let circle = |r: f64, k: usize, n: usize| {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        Point3::new(r * a.cos(), r * a.sin(), 0.0)
    };
    let positions: Vec<Point3<f64>> = (0..n).map(|k| circle(1.0, k, n)).collect();
    PolyMesh::new(positions.clone(), vec![(0..n).collect()]).unwrap();
    let mut repeated: Vec<usize> = (0..n).collect();
    repeated[n - 1] = 17;
    refused(
        "a million-gon with a vertex twice",
        PolyMesh::new(positions, vec![repeated]),
        |e| {
            matches!(
                e,
                MeshError::RepeatedIndex {
                    face: 0,
                    vertex: 17
                }
            )
        },
        &["vertex 17"],
    );

    let n = 20_000;
    let positions: Vec<Point3<f64>> = (0..n)
        .map(|k| circle(1.0, k, n))
        .chain((0..n).map(|k| circle(1.001, k, n)))
        .collect();
    let mut faces: Vec<Vec<usize>> = (0..n)
        .map(|i| vec![(i + 1) % n, i, n + i, n + (i + 1) % n])
        .collect();
    faces.push((0..n).collect());
    let ring = PolyMesh::new(positions, faces).unwrap();
    let found = pattern::solve(&ring, &{
        let mut o = quick();
        o.bond = Bond::Stack;
        o
    })
    .unwrap();
    assert_eq!(
        (found.pairs.len(), found.non_quad.clone()),
        (n / 2, vec![n])
    );
    assert!(
        started.elapsed() < Duration::from_secs(10),
        "took {:?}",
        started.elapsed()
    );
}

#[test]
fn bad_pattern_options_are_refused() {
    let grid = generate::grid(4, 4);
    for weight in [f64::NAN, -1.0, -0.0001, f64::INFINITY, f64::NEG_INFINITY] {
        for bond in [Bond::Staggered { weight }, Bond::RunningBond { weight }] {
            let options = {
                let mut o = quick();
                o.bond = bond;
                o
            };
            refused(
                &format!("{bond:?}"),
                pattern::solve(&grid, &options),
                |e| matches!(e, PatternError::InvalidWeight { .. }),
                &["bond weight", ">= 0"],
            );
        }
    }
    // Far too large weights made CBC call valid programs infeasible (1e20) or abort the
    // process (1e25 and up).
    for weight in [1000.5, 1e20, 1e300] {
        for bond in [Bond::Staggered { weight }, Bond::RunningBond { weight }] {
            let options = {
                let mut o = quick();
                o.bond = bond;
                o
            };
            refused(
                &format!("{bond:?}"),
                pattern::solve(&grid, &options),
                |e| matches!(e, PatternError::WeightTooLarge { max: 1000.0, .. }),
                &["larger than 1000"],
            );
        }
    }
    // Weights at the ends of the range solve (CBC's numerics hold).
    for weight in [0.0, pattern::MAX_WEIGHT] {
        for bond in [Bond::Staggered { weight }, Bond::RunningBond { weight }] {
            pattern::solve(&grid, &{
                let mut o = quick();
                o.bond = bond;
                o
            })
            .unwrap();
        }
    }
    for seconds in [-1.0, -1e-9, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        refused(
            &format!("{seconds} s"),
            PatternOptions::time_limit_from_secs(seconds),
            |e| matches!(e, PatternError::InvalidTimeLimit { .. }),
            &["time limit"],
        );
    }
    // Graceful: huge finite limits are cut to MAX_TIME_LIMIT_SECONDS; Duration::MAX works.
    let longest = Duration::from_secs(pattern::MAX_TIME_LIMIT_SECONDS);
    assert_eq!(
        PatternOptions::time_limit_from_secs(1e300).unwrap(),
        longest
    );
    assert_eq!(PatternOptions::time_limit_from_secs(2e19).unwrap(), longest);
    assert_eq!(
        PatternOptions::time_limit_from_secs(-0.0).unwrap(),
        Duration::ZERO
    );
    let forever = pattern::solve(&grid, &{
        let mut o = PatternOptions::default();
        o.time_limit = Duration::MAX;
        o
    })
    .unwrap();
    assert_eq!(forever.status, pattern::SolveStatus::Optimal);
    // Time limit 0: the best start, at once; its bound is still proven.
    let zero = pattern::solve(&grid, &{
        let mut o = PatternOptions::default();
        o.time_limit = Duration::ZERO;
        o
    })
    .unwrap();
    assert!(zero.bound >= zero.objective && zero.seconds < 1.0);

    let forced = |pairs: Vec<[usize; 2]>, excluded: Vec<usize>| {
        let mut o = quick();
        o.forced_pairs = pairs;
        o.excluded_faces = excluded;
        o
    };
    type Row = (
        &'static str,
        PatternOptions,
        fn(&PatternError) -> bool,
        &'static [&'static str],
    );
    let rows: Vec<Row> = vec![
        (
            "forced face out of range",
            forced(vec![[0, 99]], vec![]),
            |e| {
                matches!(
                    e,
                    PatternError::FaceOutOfRange {
                        face: 99,
                        face_count: 16
                    }
                )
            },
            &["face 99", "16 faces"],
        ),
        (
            "forced usize::MAX",
            forced(vec![[usize::MAX, 0]], vec![]),
            |e| matches!(e, PatternError::FaceOutOfRange { .. }),
            &["does not exist"],
        ),
        (
            "forced pair not adjacent",
            forced(vec![[0, 5]], vec![]),
            |e| matches!(e, PatternError::ForcedNotAdjacent { a: 0, b: 5 }),
            &["[0, 5]"],
        ),
        (
            "forced pair of one face",
            forced(vec![[3, 3]], vec![]),
            |e| matches!(e, PatternError::ForcedTwice { face: 3 }),
            &["face 3"],
        ),
        (
            "face in two forced pairs",
            forced(vec![[0, 1], [1, 2]], vec![]),
            |e| matches!(e, PatternError::ForcedTwice { face: 1 }),
            &["face 1"],
        ),
        (
            "forced and excluded",
            forced(vec![[0, 1]], vec![1]),
            |e| matches!(e, PatternError::ForcedExcluded { face: 1 }),
            &["face 1"],
        ),
        (
            "excluded out of range",
            forced(vec![], vec![16]),
            |e| matches!(e, PatternError::FaceOutOfRange { face: 16, .. }),
            &["face 16"],
        ),
    ];
    for (what, options, expected, words) in rows {
        refused(what, pattern::solve(&grid, &options), expected, words);
    }
    let triangles = generate::triangulate_quads(&generate::grid(2, 1));
    refused(
        "forced pair of triangles",
        pattern::solve(&triangles, &forced(vec![[0, 1]], vec![])),
        |e| {
            matches!(
                e,
                PatternError::ForcedNonQuad {
                    face: 0,
                    corners: 3
                }
            )
        },
        &["face 0", "3 corners"],
    );
    // Graceful: excluding a face twice, or every face.
    assert_eq!(
        pattern::solve(&grid, &forced(vec![], vec![2, 2]))
            .unwrap()
            .excluded,
        vec![2]
    );
    let all = pattern::solve(&grid, &forced(vec![], (0..16).collect())).unwrap();
    assert_eq!(
        (all.pairs.len(), all.unpaired.len(), all.excluded.len()),
        (0, 0, 16)
    );
}

#[test]
fn bad_tile_sizes_are_refused() {
    let grid = generate::grid(4, 4);
    let found = pattern::solve(&grid, &{
        let mut o = PatternOptions::default();
        o.time_limit = Duration::ZERO;
        o
    })
    .unwrap();
    let finish = FinishOptions::for_spec(&UNIT_TILE);
    let build = |spec: &TileSpec, finish: &FinishOptions| {
        pipeline::tiles_for_pattern(&grid, None, found.clone(), spec, finish)
    };
    let invalid = |name: &'static str| move |e: &Error| matches!(e, Error::Tiles(TileError::InvalidSpec { name: n, .. }) if *n == name);
    for (name, values) in [
        ("length", [0.0, -1.9, f64::NAN, f64::INFINITY]),
        ("width", [0.0, -0.95, f64::NAN, f64::INFINITY]),
        ("thickness", [0.0, -0.1, f64::NAN, f64::INFINITY]),
    ] {
        for value in values {
            let mut spec = UNIT_TILE;
            *match name {
                "length" => &mut spec.length,
                "width" => &mut spec.width,
                _ => &mut spec.thickness,
            } = value;
            refused(
                &format!("{name} {value}"),
                build(&spec, &finish),
                invalid(name),
                &[name],
            );
        }
    }
    for joint in [-0.1, f64::NAN, f64::INFINITY] {
        refused(
            &format!("joint {joint}"),
            build(&TileSpec { joint, ..UNIT_TILE }, &finish),
            invalid("joint"),
            &["joint"],
        );
    }
    refused(
        "tile larger than the shell",
        build(
            &TileSpec {
                length: 100.0,
                ..UNIT_TILE
            },
            &finish,
        ),
        |e| matches!(e, Error::Tiles(TileError::TileLargerThanMesh { .. })),
        &["larger than the whole mesh", "same units"],
    );
    // A tile far smaller than the faces (metres on millimetres) would need gigabytes to cut.
    refused(
        "tile a million times smaller than the faces",
        build(
            &TileSpec {
                length: 1.9e-6,
                width: 0.95e-6,
                thickness: 1e-7,
                joint: 1e-7,
            },
            &FinishOptions::for_spec(&TileSpec {
                length: 1.9e-6,
                width: 0.95e-6,
                thickness: 1e-7,
                joint: 1e-7,
            }),
        ),
        |e| {
            matches!(
                e,
                Error::TileTooSmall {
                    mesh: "quad mesh",
                    span: 1.0,
                    ..
                }
            )
        },
        &["tiny", "face", "quad mesh", "same units"],
    );
    let with = |f: fn(&mut FinishOptions)| {
        let mut options = finish;
        f(&mut options);
        options
    };
    refused(
        "negative cut tolerance",
        build(&UNIT_TILE, &with(|o| o.tolerance = -1.0)),
        invalid("tolerance"),
        &["tolerance"],
    );
    refused(
        "NaN minimum kept width",
        build(&UNIT_TILE, &with(|o| o.min_kept_width = f64::NAN)),
        invalid("min_kept_width"),
        &["min_kept_width"],
    );
    refused(
        "infinite support band",
        build(
            &UNIT_TILE,
            &with(|o| o.sequence.support_band = f64::INFINITY),
        ),
        invalid("support_band"),
        &["support_band"],
    );
    refused(
        "zero up direction",
        build(&UNIT_TILE, &with(|o| o.sequence.up = Vector3::zeros())),
        |e| matches!(e, Error::Tiles(TileError::NoUpDirection { up }) if *up == [0.0; 3]),
        &["up direction [0.0, 0.0, 0.0] is no direction", "0,0,1"],
    );
    refused(
        "NaN up direction",
        build(
            &UNIT_TILE,
            &with(|o| o.sequence.up = Vector3::new(0.0, f64::NAN, 1.0)),
        ),
        |e| matches!(e, Error::Tiles(TileError::NoUpDirection { .. })),
        &["up direction"],
    );

    // Patterns that do not fit the mesh (read from a file made for another mesh).
    let other = pattern::solve(&generate::grid(2, 2), &quick()).unwrap();
    refused(
        "pattern of another mesh",
        pipeline::tiles_for_pattern(&grid, None, other, &UNIT_TILE, &finish),
        |e| {
            matches!(
                e,
                Error::PatternMismatch {
                    pattern_faces: 4,
                    mesh_faces: 16
                }
            )
        },
        &["4 faces", "has 16"],
    );
    let edited = |f: fn(&mut Pattern)| {
        let mut p = found.clone();
        f(&mut p);
        pipeline::tiles_for_pattern(&grid, None, p, &UNIT_TILE, &finish)
    };
    refused(
        "pair out of range",
        edited(|p| p.pairs.push([0, 40])),
        |e| {
            matches!(
                e,
                Error::Tiles(TileError::FaceOutOfRange { face: 40, .. })
                    | Error::Tiles(TileError::FaceUsedTwice { face: 0 })
            )
        },
        &["face"],
    );
    refused(
        "pair not adjacent",
        edited(|p| p.pairs = vec![[0, 15]]),
        |e| matches!(e, Error::Tiles(TileError::NotAdjacent { a: 0, b: 15 })),
        &["[0, 15]"],
    );
    refused(
        "face in two tiles",
        edited(|p| p.unpaired.push(p.pairs[0][0])),
        |e| matches!(e, Error::Tiles(TileError::FaceUsedTwice { .. })),
        &["more than one tile"],
    );
    let triangles = generate::triangulate_quads(&generate::grid(2, 1));
    let mut on_triangles = pattern::solve(&triangles, &quick()).unwrap();
    on_triangles.pairs = vec![[0, 1]];
    refused(
        "pair of triangles",
        tiles::build(&triangles, &on_triangles, &UNIT_TILE),
        |e| {
            matches!(
                e,
                TileError::NotQuad {
                    face: 0,
                    corners: 3
                }
            )
        },
        &["face 0", "3 corners"],
    );
}

#[test]
fn bad_remesh_options_are_refused() {
    let surface = generate::triangulate_quads(&generate::grid(6, 6));
    let with = |f: fn(&mut RemeshOptions)| {
        let mut options = {
            let mut o = RemeshOptions::default();
            o.target_edge = 0.5;
            o.time_limit = Duration::from_secs(20);
            o
        };
        f(&mut options);
        remesh::remesh(&surface, &options).map(|r| r.quads.face_count())
    };
    type Row = (
        &'static str,
        fn(&mut RemeshOptions),
        fn(&RemeshError) -> bool,
        &'static [&'static str],
    );
    let rows: Vec<Row> = vec![
        (
            "target edge 0",
            |o| o.target_edge = 0.0,
            |e| matches!(e, RemeshError::BadTargetEdge(_)),
            &["target edge 0"],
        ),
        (
            "target edge -1",
            |o| o.target_edge = -1.0,
            |e| matches!(e, RemeshError::BadTargetEdge(_)),
            &["target edge -1"],
        ),
        (
            "target edge NaN",
            |o| o.target_edge = f64::NAN,
            |e| matches!(e, RemeshError::BadTargetEdge(_)),
            &["target edge NaN"],
        ),
        (
            "target edge inf",
            |o| o.target_edge = f64::INFINITY,
            |e| matches!(e, RemeshError::BadTargetEdge(_)),
            &["target edge inf"],
        ),
        (
            "target edge larger than the surface",
            |o| o.target_edge = 100.0,
            |e| matches!(e, RemeshError::TargetEdgeTooLarge { .. }),
            &["too large"],
        ),
        (
            "target edge 1e300",
            |o| o.target_edge = 1e300,
            |e| matches!(e, RemeshError::TargetEdgeTooLarge { .. }),
            &["too large"],
        ),
        (
            "target edge tiny",
            |o| o.target_edge = 1e-5,
            |e| matches!(e, RemeshError::TargetEdgeTooSmall { .. }),
            &["quads", "limit"],
        ),
        (
            "target edge 1e-300",
            |o| o.target_edge = 1e-300,
            |e| matches!(e, RemeshError::TargetEdgeTooSmall { .. }),
            &["limit"],
        ),
        (
            "zero direction",
            |o| o.direction = FieldDirection::Vector([0.0; 3]),
            |e| matches!(e, RemeshError::BadDirection(_)),
            &["direction"],
        ),
        (
            "NaN direction",
            |o| o.direction = FieldDirection::Vector([f64::NAN, 0.0, 0.0]),
            |e| matches!(e, RemeshError::BadDirection(_)),
            &["direction"],
        ),
        (
            "infinite angle",
            |o| o.direction = FieldDirection::Angle(f64::INFINITY),
            |e| matches!(e, RemeshError::BadAngle(_)),
            &["angle"],
        ),
        (
            "NaN shape-up tolerance",
            |o| (o.shapeup, o.shapeup_tolerance) = (true, f64::NAN),
            |e| matches!(e, RemeshError::BadShapeupTolerance(_)),
            &["shape-up"],
        ),
        (
            "negative renormalisation",
            |o| o.renormalisation = -0.5,
            |e| matches!(e, RemeshError::BadRenormalisation(_)),
            &["renormalisation", "from 0"],
        ),
        (
            "NaN renormalisation",
            |o| o.renormalisation = f64::NAN,
            |e| matches!(e, RemeshError::BadRenormalisation(_)),
            &["renormalisation"],
        ),
        (
            "time limit 0",
            |o| o.time_limit = Duration::ZERO,
            |e| matches!(e, RemeshError::TimeLimit { .. }),
            &["time limit"],
        ),
    ];
    for (what, edit, expected, words) in rows {
        refused(what, with(edit), expected, words);
    }
    for seconds in [-1.0, f64::NAN, f64::INFINITY] {
        refused(
            &format!("remesh time limit {seconds}"),
            RemeshOptions::time_limit_from_secs(seconds),
            |e| matches!(e, RemeshError::BadTimeLimit(_)),
            &["time limit"],
        );
    }
    // Graceful: a direction along the normal (the field falls back to curvature) and a huge
    // angle still give quads.
    assert!(with(|o| o.direction = FieldDirection::Vector([0.0, 0.0, 1.0])).unwrap() > 0);
    assert!(with(|o| o.direction = FieldDirection::Angle(1e300)).unwrap() > 0);

    // Surfaces the remesher cannot take.
    let options = {
        let mut o = RemeshOptions::default();
        o.target_edge = 0.2;
        o
    };
    let flat = PolyMesh::new(
        points(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]),
        vec![vec![0, 1, 2]],
    )
    .unwrap();
    refused(
        "zero-area surface",
        remesh::remesh(&flat, &options),
        |e| matches!(e, RemeshError::UnsupportedInput(_)),
        &["no area"],
    );
    // Two squares touching at (1, 1): that vertex third in the file, then last. The message
    // names the file's number for it, not the order the faces first use it in (it said
    // "vertex 2" for both).
    let others = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [2.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    for (what, shared, expected) in [
        (
            "surfaces touching at a vertex",
            2,
            "vertex 2 (counted from 0) at (1.0000, 1.0000, 0.0000)",
        ),
        (
            "surfaces touching at a vertex listed last",
            6,
            "vertex 6 (counted from 0) at (1.0000, 1.0000, 0.0000)",
        ),
    ] {
        let mut xyz = others.to_vec();
        xyz.insert(shared, [1.0, 1.0, 0.0]);
        // The other six in the file's order, around the shared vertex.
        let other: Vec<usize> = (0..7).filter(|&v| v != shared).collect();
        let faces = vec![
            vec![other[0], other[1], shared, other[2]],
            vec![shared, other[3], other[4], other[5]],
        ];
        let bowtie = generate::triangulate_quads(&PolyMesh::new(points(&xyz), faces).unwrap());
        refused(
            what,
            remesh::remesh(&bowtie, &options),
            |e| matches!(e, RemeshError::UnsupportedInput(_)),
            &[expected],
        );
    }

    // The whole pipeline refuses a tile far too small for the surface before remeshing.
    let tiny = TileSpec {
        length: 2e-6,
        width: 1e-6,
        thickness: 1e-7,
        joint: 0.0,
    };
    let remesh_options = {
        let mut o = RemeshOptions::default();
        o.target_edge = 1e-6;
        o
    };
    let result = pipeline::tile_surface(
        &surface,
        &remesh_options,
        &quick(),
        &tiny,
        &FinishOptions::for_spec(&tiny),
        &mut tilepattern::control::Control::none(),
    );
    refused(
        "pipeline with a tiny tile",
        result.map(|_| ()),
        |e| {
            matches!(
                e,
                Error::TileTooSmall {
                    mesh: "surface",
                    ..
                }
            )
        },
        &["surface", "same units"],
    );
}

/// The command line: each row is the arguments, the exit code and words that stderr must
/// hold (exit 0 rows: the output file or stdout is checked too). Never a panic.
#[test]
fn the_command_line_reports_bad_input() {
    let dir = std::env::temp_dir().join(format!("tp-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let write = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\n";
    let nan = write("nan.obj", "v 0 0 0\nv 1 0 nan\nv 1 1 0\nf 1 2 3\n");
    let inf = write("inf.obj", "v 0 0 0\nv 1 0 0\nv 1 -inf 0\nf 1 2 3\n");
    let far = write("far.obj", "v 0 0 0\nv 1e15 0 0\nv 1 1 0\nf 1 2 3\n");
    let range = write("range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 7\n");
    let zero_index = write("zero.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 0 1 2\n");
    let before_first = write("before.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf -1 -2 -4\n");
    let repeated = write("repeated.obj", &format!("{square}f 1 2 2 4\n"));
    let duplicate = write("duplicate.obj", &format!("{square}f 1 2 3 4\nf 3 4 1 2\n"));
    let fan = write(
        "fan.obj",
        "v 0 0 0\nv 1 0 0\nv 0.5 1 0\nv 0.5 -1 0\nv 0.5 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
    );
    let empty = write("empty.obj", "");
    let line = write(
        "line.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 3 0 0\nv 4 0 0\nf 1 2 3\nf 2 3 4\nf 3 4 5\n",
    );
    let junk = write("junk.obj", "v 0 0\nf 1 2 3\n");
    let binary = write("binary.obj", "\u{0}\u{1}\u{2}v\u{0}");
    let quads = write(
        "quads.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n",
    );
    let relative = write(
        "relative.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\nv 2 0 0\nv 2 1 0\nf -5 -2 -1 -4\n",
    );
    let triangles = write(
        "triangles.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n",
    );
    let bowtie = write(
        "bowtie.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 1 0\nv 2 2 0\nv 1 2 0\nf 1 2 3 4\nf 3 5 6 7\n",
    );
    let pieces = write(
        "pieces.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 6 1 0\nv 5 1 0\nf 1 2 3 4\nf 5 6 7 8\n",
    );
    let sliver = write(
        "sliver.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 0 0\nv 2 1 0\nf 1 2 5 4\nf 2 3 6 5\n",
    );
    let wrong_pairs = write(
        "wrong.json",
        r#"{"faces": 2, "pairs": [[0, 7]], "unpaired": [], "continuous_joints": 0, "shifted_pairs": 0, "objective": 1, "bound": 1, "gap": 0, "status": "optimal", "seconds": 0}"#,
    );
    let other_mesh = write(
        "other.json",
        r#"{"faces": 9, "pairs": [], "unpaired": [], "continuous_joints": 0, "shifted_pairs": 0, "objective": 0, "bound": 0, "gap": 0, "status": "optimal", "seconds": 0}"#,
    );
    let not_json = write("not.json", "pairs: 0 1");
    let mixed = write(
        "mixed.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nf 1 2 3 4\nf 2 5 3\n",
    );
    let zone_typo = write("typo-zones.txt", "0 staggered\n1 herringbon\n");
    let zone_range = write("range-zones.txt", "0-2 stack\n");
    let zone_line = write("line-zones.txt", "0 stack staggered\n");
    let zone_array = write("array-zones.json", "[\"stack\"]");
    let zone_herringbone = write("herringbone-zones.txt", "1 herringbone\n");
    let pairs = out("pairs.json");
    let tiles = out("tiles.obj");
    let tile = ["--tile", "1900x950x100", "--units", "m"];
    let with_tile = |args: &[&str]| -> Vec<String> {
        args.iter().chain(&tile).map(|s| s.to_string()).collect()
    };

    type Row = (Vec<String>, i32, &'static [&'static str]);
    let args = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    let rows: Vec<Row> = vec![
        // Meshes.
        (
            args(&["match", &nan]),
            1,
            &["nan.obj", "vertex 1", "NaN", "counted from 0"],
        ),
        (args(&["match", &inf]), 1, &["vertex 2"]),
        (args(&["match", &far]), 1, &["vertex 1", "at most 1e12"]),
        (args(&["match", &range]), 1, &["face 0", "vertex 6"]),
        (args(&["match", &zero_index]), 1, &["line 4", "index 0"]),
        (args(&["match", &before_first]), 1, &["line 4", "-4"]),
        // A corner given twice in a row is one corner (a triangle written as a quad, as
        // Rhino stores it); kept as given, it is refused.
        (
            args(&["match", &repeated]),
            0,
            &[
                "lost a corner",
                "given twice in a row",
                "none of the 1 faces is a quad",
            ],
        ),
        (
            args(&["--weld", "off", "match", &repeated]),
            1,
            &["face 0", "vertex 1", "more than once"],
        ),
        // A face given twice is removed while reading (welding, on by default), with a
        // warning; kept as given, it is refused.
        (
            args(&["match", &duplicate]),
            0,
            &[
                "warning [vertices_welded]",
                "1 faces with a corner given twice or repeating",
            ],
        ),
        (
            args(&["match", &duplicate, "--weld", "off"]),
            1,
            &["face 1", "repeats face 0"],
        ),
        (args(&["match", &fan]), 1, &["edge 0-1", "3 faces"]),
        // Before: "2 faces: 0 tiles", exit 0, and not a word more.
        (
            args(&["match", &triangles]),
            0,
            &[
                "warning: none of the 2 faces is a quad",
                "tilepattern remesh",
                "tilepattern run",
            ],
        ),
        (
            args(&["match", &mixed]),
            0,
            &["warning: 1 of the 2 faces are not quads"],
        ),
        (args(&["match", &empty]), 1, &["empty"]),
        (args(&["match", &junk]), 1, &["line 1", "x, y and z"]),
        (args(&["match", &binary]), 1, &["binary.obj"]),
        (
            args(&["match", "/nonexistent/x.obj"]),
            1,
            &["x.obj", "No such file"],
        ),
        (args(&["match", dir.to_str().unwrap()]), 1, &["cannot use"]),
        // Pattern options.
        (
            args(&["match", &quads, "--weight", "nan"]),
            1,
            &["bond weight NaN"],
        ),
        (
            args(&["match", &quads, "--weight=-1"]),
            1,
            &["bond weight -1"],
        ),
        (
            args(&[
                "match",
                &quads,
                "--pattern",
                "running-bond",
                "--weight",
                "1e30",
            ]),
            1,
            &["bond weight 1e30 is larger than 1000"],
        ),
        (
            args(&["match", &quads, "--weight", "heavy"]),
            2,
            &["--weight"],
        ),
        // Zones (issue 20).
        (
            args(&["match", &quads, "--zones", &zone_typo]),
            1,
            &["typo-zones.txt", "line 2", "'herringbon' is not a bond"],
        ),
        (
            args(&["match", &quads, "--zones", &zone_range]),
            1,
            &["line 1", "face 2 is out of range", "2 faces"],
        ),
        (
            args(&["match", &quads, "--zones", &zone_line]),
            1,
            &["line 1", "FACE BOND or FIRST-LAST BOND"],
        ),
        (
            args(&["match", &quads, "--zones", &zone_array]),
            1,
            &["1 zones for a quad mesh of 2 faces"],
        ),
        (
            args(&["match", &quads, "--zones", "/nonexistent/zones.txt"]),
            1,
            &["cannot read the zones file", "zones.txt"],
        ),
        (
            args(&[
                "match",
                &quads,
                "--zones",
                &zone_herringbone,
                "--courses",
                "level",
            ]),
            1,
            &["herringbone", "courses free"],
        ),
        (
            args(&[
                "match",
                &quads,
                "--pattern",
                "stack",
                "--weight",
                "nan",
                "--zones",
                &zone_herringbone,
            ]),
            1,
            &["zone of face 1", "bond weight NaN"],
        ),
        (
            args(&["match", &quads, "--time-limit=-1"]),
            1,
            &["time limit -1"],
        ),
        (
            args(&["match", &quads, "--time-limit", "nan"]),
            1,
            &["time limit NaN"],
        ),
        (
            args(&["match", &quads, "--time-limit", "inf"]),
            1,
            &["time limit inf"],
        ),
        (
            args(&["match", &quads, "--force", "0,7"]),
            1,
            &["face 7", "2 faces"],
        ),
        (
            args(&["match", &quads, "--force", "0"]),
            2,
            &["pair of face indices"],
        ),
        (
            args(&["match", &quads, "--force=-1,0"]),
            2,
            &["pair of face indices"],
        ),
        (args(&["match", &quads, "--exclude", "5"]), 1, &["face 5"]),
        (args(&["match", &quads, "--exclude=-1"]), 2, &["--exclude"]),
        (
            args(&["match", &quads, "--force", "0,1", "--exclude", "1"]),
            1,
            &["face 1", "excluded"],
        ),
        (
            args(&["match", &triangles, "--force", "0,1"]),
            1,
            &["face 0", "3 corners"],
        ),
        // Tile options.
        (
            with_tile(&["tiles", &quads, "--pairs", &wrong_pairs, "-o", &tiles]),
            1,
            &["face 7"],
        ),
        (
            with_tile(&["tiles", &quads, "--pairs", &other_mesh, "-o", &tiles]),
            1,
            &["9 faces", "has 2"],
        ),
        (
            with_tile(&["tiles", &quads, "--pairs", &not_json, "-o", &tiles]),
            1,
            &["not.json", "not the JSON"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--tile",
                "0x140x15",
            ]),
            2,
            &["tile length 0 mm"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--tile=-280x140x15",
            ]),
            2,
            &["tile length -280 mm"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--tile",
                "280xnanx15",
            ]),
            2,
            &["tile width NaN mm"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--tile",
                "280x140x0",
            ]),
            2,
            &["tile thickness 0 mm"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--tile",
                "280x140",
            ]),
            2,
            &["not a tile size"],
        ),
        (
            with_tile(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--joint=-5",
            ]),
            2,
            &["-5 mm must be a number >= 0"],
        ),
        (
            with_tile(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--cut-tolerance",
                "nan",
            ]),
            2,
            &["NaN mm"],
        ),
        (
            with_tile(&[
                "tiles",
                &quads,
                "--pairs",
                &other_mesh,
                "-o",
                &tiles,
                "--up",
                "0,0,0",
            ]),
            1,
            &["up direction", "is no direction", "0,0,1"],
        ),
        (args(&["match", &quads, "--json", &pairs]), 0, &[]),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &pairs,
                "-o",
                &tiles,
                "--tile",
                "280000x140000x15000",
                "--units",
                "mm",
            ]),
            1,
            &["larger than the whole mesh"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &pairs,
                "-o",
                &tiles,
                "--tile",
                "0.001x0.0005x0.0001",
                "--units",
                "m",
            ]),
            1,
            &["tiny", "same units"],
        ),
        // A joint as wide as the tile, a tile thicker than long: refused before the units
        // are guessed (a joint of 1000 was refused as a mesh of no plausible size).
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &pairs,
                "-o",
                &tiles,
                "--tile",
                "280x140x15",
                "--joint",
                "1000",
            ]),
            1,
            &["joint 1000 is not smaller than the tile's width 140"],
        ),
        (
            args(&[
                "tiles",
                &quads,
                "--pairs",
                &pairs,
                "-o",
                &tiles,
                "--tile",
                "280x140x1e9",
            ]),
            1,
            &["thickness 1000000000 is not smaller than the tile's length 280"],
        ),
        // Remesh options.
        (
            args(&["remesh", &quads, "--edge", "0", "-o", &out("q.obj")]),
            1,
            &["target edge 0"],
        ),
        (
            args(&["remesh", &quads, "--edge", "nan", "-o", &out("q.obj")]),
            1,
            &["target edge NaN"],
        ),
        (
            args(&["remesh", &quads, "--edge=-0.1", "-o", &out("q.obj")]),
            1,
            &["target edge -0.1"],
        ),
        (
            args(&["remesh", &quads, "--edge", "1e300", "-o", &out("q.obj")]),
            1,
            &["too large"],
        ),
        (
            args(&["remesh", &quads, "--edge", "1e-9", "-o", &out("q.obj")]),
            1,
            &["use a larger edge"],
        ),
        (
            args(&[
                "remesh",
                &quads,
                "--edge",
                "0.1",
                "--direction",
                "0,0,0",
                "-o",
                &out("q.obj"),
            ]),
            1,
            &["direction"],
        ),
        (
            args(&[
                "remesh",
                &quads,
                "--edge",
                "0.1",
                "--direction",
                "1,0",
                "-o",
                &out("q.obj"),
            ]),
            2,
            &["not a direction"],
        ),
        (
            args(&[
                "remesh",
                &quads,
                "--edge",
                "0.1",
                "--angle",
                "inf",
                "-o",
                &out("q.obj"),
            ]),
            1,
            &["angle inf"],
        ),
        (
            args(&[
                "remesh",
                &quads,
                "--edge",
                "0.1",
                "--time-limit=-1",
                "-o",
                &out("q.obj"),
            ]),
            1,
            &["time limit -1"],
        ),
        (
            args(&["remesh", &bowtie, "--edge", "0.1", "-o", &out("q.obj")]),
            1,
            &["vertex 2"],
        ),
        (
            args(&["demo", "--span", "0", "--out", &out("demo")]),
            1,
            &["span"],
        ),
        (
            args(&["demo", "--span", "nan", "--out", &out("demo")]),
            1,
            &["span"],
        ),
        (
            args(&[
                "run",
                &quads,
                "--tile",
                "280x140x15",
                "--units",
                "mm",
                "--out",
                &out("run"),
            ]),
            1,
            &["target edge 150", "too large"],
        ),
        // Corners all on a line: no area in any unit (before: the units message).
        (
            args(&["run", &line, "--tile", "280x140x15", "--out", &out("line")]),
            1,
            &["no area", "on a line", "export the surface again"],
        ),
        (args(&["frobnicate"]), 2, &["unrecognized subcommand"]),
        // Graceful rows: accepted, with the documented result.
        (
            args(&["match", &relative, "--json", &out("relative.json")]),
            0,
            &["2 faces: 1 tiles"],
        ),
        (
            args(&["match", &triangles, "--json", &out("triangles.json")]),
            0,
            &["0 tiles, 0 unpaired"],
        ),
        (
            args(&["match", &bowtie, "--json", &out("bowtie.json")]),
            0,
            &["0 tiles, 2 unpaired"],
        ),
        (
            args(&["match", &pieces, "--json", &out("pieces.json")]),
            0,
            &["0 tiles, 2 unpaired"],
        ),
        (
            // Its zero-length edge is the point: kept as written, not welded.
            args(&[
                "match",
                &sliver,
                "--weld",
                "off",
                "--json",
                &out("sliver.json"),
            ]),
            0,
            &["1 tiles, 0 unpaired"],
        ),
        (
            args(&[
                "match",
                &quads,
                "--time-limit",
                "0",
                "--json",
                &out("zero.json"),
            ]),
            0,
            &["1 tiles"],
        ),
        (
            args(&[
                "match",
                &quads,
                "--time-limit",
                "1e300",
                "--json",
                &out("long.json"),
            ]),
            0,
            &["Optimal"],
        ),
    ];
    for (args, code, words) in rows {
        let output = Command::new(env!("CARGO_BIN_EXE_tilepattern"))
            .args(&args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(
            output.status.code(),
            Some(code),
            "{args:?}: stderr {stderr}"
        );
        for word in words {
            assert!(
                stderr.contains(word),
                "{args:?}: stderr \"{stderr}\" lacks \"{word}\""
            );
        }
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    }
    // The graceful rows wrote what they promise.
    let read = |name: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(dir.join(name)).unwrap()).unwrap()
    };
    assert_eq!(read("relative.json")["pairs"], serde_json::json!([[0, 1]]));
    assert_eq!(
        read("triangles.json")["non_quad"],
        serde_json::json!([0, 1])
    );
    assert_eq!(read("pieces.json")["unpaired"], serde_json::json!([0, 1]));
    let _ = std::fs::remove_dir_all(&dir);
}
