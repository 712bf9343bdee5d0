//! Mesh validation, OBJ reading and writing.

mod common;

use nalgebra::Point3;
use tilepattern::mesh::{MeshError, PolyMesh, generate, obj};

fn square() -> Vec<Point3<f64>> {
    vec![
        Point3::new(0.0, 0.0, 0.0),
        Point3::new(1.0, 0.0, 0.0),
        Point3::new(1.0, 1.0, 0.0),
        Point3::new(0.0, 1.0, 0.0),
    ]
}

#[test]
fn obj_round_trip_keeps_order_precision_and_ngons() {
    let mut mesh = common::split_into_quads(&common::polygon(5));
    let positions: Vec<Point3<f64>> = mesh
        .positions()
        .iter()
        .map(|p| p * (1.0 / 3.0) + nalgebra::Vector3::new(0.1, 1e-9, 7.0))
        .collect();
    let mut faces = mesh.faces().to_vec();
    faces.reverse();
    faces.push(vec![0, 1, 2]);
    let extra_vertex = positions.len();
    let mut positions = positions;
    positions.push(Point3::new(-5.0, -5.0, 0.0));
    faces.push(vec![1, 0, extra_vertex]);
    mesh = PolyMesh::new(positions, faces).unwrap();
    let text = obj::to_string(&mesh);
    assert_eq!(obj::parse(&text).unwrap(), mesh);

    let dir = std::env::temp_dir().join(format!("tp-mesh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("m.obj");
    obj::write(&mesh, &path).unwrap();
    assert_eq!(obj::read(&path).unwrap(), mesh);
}

#[test]
fn obj_reader_understands_common_face_forms() {
    let text = "# comment\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\ng part\nusemtl x\nf 1/1/1 2/1/1 3//1 -1\n";
    let mesh = obj::parse(text).unwrap();
    assert_eq!(mesh.faces(), &[vec![0, 1, 2, 3]]);
}

#[test]
fn obj_reader_joins_continued_lines_and_reads_old_face_names() {
    // A face continued over two lines with a backslash, and one given as `fo`; a bad number
    // after a continuation is named by the line the statement starts on.
    let text =
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 2 1 0\nf 1 2 \\\n  3 4\nfo 2 5 6 3\n";
    let mesh = obj::parse(text).unwrap();
    assert_eq!(mesh.faces(), &[vec![0, 1, 2, 3], vec![1, 4, 5, 2]]);
    let bad = obj::parse("v 0 0 0\nv 1 \\\n zero 0\n").unwrap_err();
    assert!(matches!(bad, MeshError::ObjSyntax { line: 2, .. }), "{bad}");
}

#[test]
fn an_obj_of_nurbs_surfaces_is_named_so_and_a_mesh_asked_for() {
    // A surface Rhino exports to OBJ as NURBS: control points and a `surf`, no faces.
    let text = "v 0 0 0\nv 5 0 0\nv 0 5 0\nv 5 5 1\ncstype bspline\ndeg 1 1\nsurf 0 1 0 1 1 2 3 4\nparm u 0 0 1 1\nparm v 0 0 1 1\nend\n";
    let error = obj::parse(text).unwrap_err();
    assert!(
        matches!(error, MeshError::Format { format: "OBJ", .. }),
        "{error}"
    );
    let message = error.to_string();
    assert!(
        message.contains("free-form") && message.contains("as a mesh"),
        "{message}"
    );
    // With faces beside it, the faces are read and the free-form part left.
    let mixed = format!("{text}f 1 2 4 3\n");
    assert_eq!(obj::parse(&mixed).unwrap().face_count(), 1);
    // An empty file is still just empty.
    assert!(matches!(
        obj::parse("v 0 0 0\n").unwrap_err(),
        MeshError::Empty { .. }
    ));
}

#[test]
fn obj_reader_names_the_bad_line() {
    let bad_number = obj::parse("v 0 0 0\nv 1 zero 0\n").unwrap_err();
    assert_eq!(
        bad_number,
        MeshError::ObjSyntax {
            line: 2,
            message: "'zero' is not a number".into()
        }
    );
    let zero = obj::parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").unwrap_err();
    assert!(
        matches!(zero, MeshError::ObjSyntax { line: 4, .. }),
        "{zero}"
    );
    let before_first = obj::parse("v 0 0 0\nf -1 -2 -3\n").unwrap_err();
    assert!(
        matches!(before_first, MeshError::ObjSyntax { line: 2, .. }),
        "{before_first}"
    );
    let missing = obj::read(std::path::Path::new("/nonexistent/shell.obj")).unwrap_err();
    assert!(matches!(missing, MeshError::Io { .. }), "{missing}");
}

#[test]
fn every_validation_error_names_its_culprit() {
    assert_eq!(
        PolyMesh::new(vec![], vec![]).unwrap_err(),
        MeshError::Empty {
            vertices: 0,
            faces: 0
        }
    );
    assert_eq!(
        PolyMesh::new(square(), vec![]).unwrap_err(),
        MeshError::Empty {
            vertices: 4,
            faces: 0
        }
    );

    let mut nan = square();
    nan[2].y = f64::NAN;
    assert_eq!(
        PolyMesh::new(nan, vec![vec![0, 1, 2, 3]]).unwrap_err(),
        MeshError::NonFiniteCoordinate { vertex: 2 }
    );
    let mut inf = square();
    inf[3].z = f64::INFINITY;
    assert_eq!(
        PolyMesh::new(inf, vec![vec![0, 1, 2, 3]]).unwrap_err(),
        MeshError::NonFiniteCoordinate { vertex: 3 }
    );

    assert_eq!(
        PolyMesh::new(square(), vec![vec![0, 1, 2, 3], vec![0, 1]]).unwrap_err(),
        MeshError::TooFewVertices { face: 1, count: 2 }
    );
    assert_eq!(
        PolyMesh::new(square(), vec![vec![0, 1, 9, 3]]).unwrap_err(),
        MeshError::IndexOutOfRange {
            face: 0,
            index: 9,
            vertex_count: 4
        }
    );
    assert_eq!(
        PolyMesh::new(square(), vec![vec![0, 1, 2, 1]]).unwrap_err(),
        MeshError::RepeatedIndex { face: 0, vertex: 1 }
    );

    let mut fan = square();
    fan.push(Point3::new(0.5, -1.0, 1.0));
    let err = PolyMesh::new(fan, vec![vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]]).unwrap_err();
    assert_eq!(
        err,
        MeshError::NonManifoldEdge {
            a: 0,
            b: 1,
            face_count: 3,
            faces: vec![0, 1, 2]
        }
    );
    assert!(err.to_string().contains("edge 0-1"), "{err}");
}

#[test]
fn generated_shell_has_square_quads_of_the_requested_edge() {
    let edge = 0.145;
    let shell = generate::corner_supported_shell(3.0, edge);
    assert!(shell.faces().iter().all(|f| f.len() == 4));
    for face in shell.faces() {
        for i in 0..4 {
            let d = (shell.positions()[face[i]] - shell.positions()[face[(i + 1) % 4]]).norm();
            assert!((d - edge).abs() < 0.05 * edge, "edge {d} far from {edge}");
        }
    }
    let (min, max) = shell.bounding_box();
    assert!(
        (max.x - min.x - 3.0).abs() < 1e-9 && min.z.abs() < 1e-9 && (max.z - 0.75).abs() < 1e-9
    );
}
