//! The tile stage and the joint report.

mod common;

use std::time::Duration;

use nalgebra::{Point3, Vector3};
use tilepattern::mesh::{PolyMesh, generate, obj};
use tilepattern::pattern::{self, Bond, Pattern, PatternOptions};
use tilepattern::report::Report;
use tilepattern::tiles::{self, TileError, TileKind, TileSpec};

/// The pattern made of exactly these pairs (the rest of the quads unpaired).
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

/// Tiles 1.9 x 0.95 x 0.1 with a 0.1 joint on a unit grid: end joints 0.1, side joints 0.05.
const SPEC: TileSpec = TileSpec {
    length: 1.9,
    width: 0.95,
    thickness: 0.1,
    joint: 0.1,
};

#[test]
fn flat_tiles_sit_on_their_faces_with_the_nominal_joint() {
    let grid = generate::grid(4, 2);
    let found = pattern_of(&grid, &[[0, 1], [2, 3], [4, 5], [6, 7]]);
    let built = tiles::build(&grid, &found, &SPEC).unwrap();
    assert_eq!(built.len(), 4);
    for tile in &built {
        assert_eq!(tile.kind, TileKind::Full);
        let f = &tile.frame;
        let [a, b] = tile.faces[..] else { panic!() };
        assert!(
            (f.origin - nalgebra::center(&grid.face_centroid(a), &grid.face_centroid(b))).norm()
                < 1e-12
        );
        assert!((f.x - Vector3::x()).norm() < 1e-12 && (f.z - Vector3::z()).norm() < 1e-12);
        assert!((f.x.cross(&f.y) - f.z).norm() < 1e-12);
        for (k, c) in tile.corners.iter().enumerate() {
            let expected_z = if k < 4 { 0.0 } else { 0.1 };
            assert!(
                (c[2] - expected_z).abs() < 1e-12,
                "corner {k} at z {}",
                c[2]
            );
            assert!(
                (c[0] - f.origin.x).abs() <= 0.95 + 1e-12
                    && (c[1] - f.origin.y).abs() <= 0.475 + 1e-12
            );
        }
    }
    let report = Report::new(&grid, &found, &built, &SPEC);
    let j = report.joints;
    assert_eq!((j.contacts, j.overlaps), (4, 0));
    assert!(
        (j.min_gap - 0.05).abs() < 1e-9 && (j.max_gap - 0.1).abs() < 1e-9,
        "{j:?}"
    );
}

#[test]
fn unpaired_quads_become_half_tiles() {
    let grid = generate::grid(3, 1);
    let found = pattern_of(&grid, &[[0, 1]]);
    let built = tiles::build(&grid, &found, &SPEC).unwrap();
    assert_eq!(
        built.iter().map(|t| t.kind).collect::<Vec<_>>(),
        vec![TileKind::Full, TileKind::Half]
    );
    let half = &built[1];
    assert_eq!(half.faces, vec![2]);
    assert_eq!(half.size, [0.95, 0.95, 0.1]);
    assert!((half.frame.origin - Point3::new(2.5, 0.5, 0.0)).norm() < 1e-12);
    let report = Report::new(&grid, &found, &built, &SPEC);
    assert_eq!((report.full_tiles, report.half_tiles), (1, 1));
    // A half tile is L/2 = 0.95 long on a unit face: 0.025 clearance at each end, so the
    // joint to the full tile is 0.05 + 0.025.
    assert_eq!(report.joints.contacts, 1);
    assert!(
        (report.joints.min_gap - 0.075).abs() < 1e-9
            && (report.joints.max_gap - 0.075).abs() < 1e-9,
        "{:?}",
        report.joints
    );
}

#[test]
fn frames_on_a_curved_shell_are_orthonormal_and_face_outwards() {
    let shell = generate::corner_supported_shell(2.0, 0.145);
    let spec = TileSpec {
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
    };
    let found = pattern::solve(&shell, &PatternOptions::default()).unwrap();
    let built = tiles::build(&shell, &found, &spec).unwrap();
    assert_eq!(built.len(), found.pairs.len() + found.unpaired.len());
    for tile in &built {
        let f = &tile.frame;
        for (u, v) in [(f.x, f.y), (f.y, f.z), (f.z, f.x)] {
            assert!(u.dot(&v).abs() < 1e-9);
        }
        assert!(
            [f.x, f.y, f.z]
                .iter()
                .all(|a| (a.norm() - 1.0).abs() < 1e-9)
        );
        assert!((f.x.cross(&f.y) - f.z).norm() < 1e-9);
        let normal: Vector3<f64> = tile.faces.iter().map(|&g| shell.face_area_vector(g)).sum();
        assert!(f.z.dot(&normal) > 0.0);
        // The bottom face lies on the surface: every face vertex is within a few mm of it.
        for &g in &tile.faces {
            for p in shell.face_points(g) {
                assert!(
                    f.to_local(&p).z.abs() < 0.005,
                    "vertex {:.4} off the tile's plane",
                    f.to_local(&p).z
                );
            }
        }
    }
}

#[test]
fn tiles_obj_has_one_closed_box_per_tile() {
    let grid = generate::grid(3, 1);
    let found = pattern_of(&grid, &[[0, 1]]);
    let built = tiles::build(&grid, &found, &SPEC).unwrap();
    let text = tiles::to_obj(&built);
    assert!(text.contains("o full_0") && text.contains("o half_1"));
    let boxes = obj::parse(&text).unwrap();
    assert_eq!((boxes.positions().len(), boxes.face_count()), (16, 12));
    // Outward normals: each box's faces point away from its centre.
    for (t, tile) in built.iter().enumerate() {
        let centre = tile.to_world(Vector3::new(0.0, 0.0, tile.size[2] / 2.0));
        for f in 6 * t..6 * t + 6 {
            assert!(
                boxes
                    .face_area_vector(f)
                    .dot(&(boxes.face_centroid(f) - centre))
                    > 0.0
            );
        }
    }
}

#[test]
fn bad_specs_and_foreign_pairs_are_refused() {
    let grid = generate::grid(3, 2);
    let ok = pattern_of(&grid, &[[0, 1]]);
    let build = |p: &Pattern, spec: &TileSpec| tiles::build(&grid, p, spec).unwrap_err();
    assert_eq!(
        build(
            &ok,
            &TileSpec {
                length: 0.0,
                ..SPEC
            }
        ),
        TileError::InvalidSpec {
            name: "length",
            value: 0.0
        }
    );
    assert!(matches!(
        build(
            &ok,
            &TileSpec {
                width: f64::NAN,
                ..SPEC
            }
        ),
        TileError::InvalidSpec { name: "width", .. }
    ));
    assert_eq!(
        build(
            &ok,
            &TileSpec {
                joint: -1.0,
                ..SPEC
            }
        ),
        TileError::InvalidSpec {
            name: "joint",
            value: -1.0
        }
    );
    assert!(matches!(
        build(
            &ok,
            &TileSpec {
                length: 280.0,
                ..SPEC
            }
        ),
        TileError::TileLargerThanMesh { .. }
    ));
    assert_eq!(
        build(&pattern_of(&grid, &[[0, 4]]), &SPEC),
        TileError::NotAdjacent { a: 0, b: 4 }
    );
    assert_eq!(
        build(&pattern_of(&grid, &[[0, 1], [1, 2]]), &SPEC),
        TileError::FaceUsedTwice { face: 1 }
    );
    assert_eq!(
        build(&pattern_of(&grid, &[[0, 17]]), &SPEC),
        TileError::FaceOutOfRange {
            face: 17,
            face_count: 6
        }
    );

    let tri = common::split_into_quads(&common::polygon(3));
    let mut faces = tri.faces().to_vec();
    faces.push(vec![1, 0, tri.positions().len()]);
    let mut positions = tri.positions().to_vec();
    positions.push(Point3::new(0.0, -3.0, 0.0));
    let with_triangle = PolyMesh::new(positions, faces).unwrap();
    let mut found = pattern_of(&with_triangle, &[]);
    found.unpaired = vec![3];
    assert_eq!(
        tiles::build(&with_triangle, &found, &SPEC).unwrap_err(),
        TileError::NotQuad {
            face: 3,
            corners: 3
        }
    );
}
