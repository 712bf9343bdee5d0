//! `--field FILE` and `--field-weight` on the command line (issue 20): the designer's
//! vectors per vertex or per face steer the quads; bad files are refused with the line or
//! the index at fault.

mod common;

use common::{plate_obj, s, scratch, tilepattern};
use nalgebra::Vector3;
use tilepattern::mesh::{PolyMesh, obj};

/// Share of interior edges of a flat quad mesh within 10 degrees of `d` or its perpendicular.
fn aligned(quads: &PolyMesh, d: Vector3<f64>) -> f64 {
    let mut uses = std::collections::BTreeMap::new();
    for face in quads.faces() {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    let p = quads.positions();
    let inner: Vec<_> = uses.iter().filter(|(_, c)| **c == 2).collect();
    let good = inner
        .iter()
        .filter(|((a, b), _)| {
            let e = p[*b].coords - p[*a].coords;
            let angle = (e.dot(&d).abs() / e.norm()).min(1.0).acos().to_degrees();
            angle.min(90.0 - angle) <= 10.0
        })
        .count();
    good as f64 / inner.len() as f64
}

#[test]
fn a_field_file_per_face_or_per_vertex_turns_the_quads() {
    let dir = scratch("cli-field");
    let n = 12;
    let surface = dir.join("plate.obj");
    std::fs::write(&surface, plate_obj(n)).unwrap();
    let a = 30f64.to_radians();
    let d = Vector3::new(a.cos(), a.sin(), 0.0);
    // Per face as JSON, per vertex as CSV (with a header, signs flipped on every other line).
    let faces = dir.join("faces.json");
    let rows: Vec<String> = (0..2 * n * n)
        .map(|_| format!("[{}, {}, 0]", d.x, d.y))
        .collect();
    std::fs::write(&faces, format!("[{}]", rows.join(", "))).unwrap();
    let vertices = dir.join("vertices.csv");
    let mut csv = String::from("x,y,z\n");
    for i in 0..(n + 1) * (n + 1) {
        let sign = if i % 2 == 0 { 1.0 } else { -3.0 };
        csv += &format!("{},{},0\n", sign * d.x, sign * d.y);
    }
    std::fs::write(&vertices, csv).unwrap();
    let remesh = |extra: &[&str], name: &str| {
        let out_path = dir.join(name);
        let mut args = vec!["remesh", s(&surface), "--edge", "0.145", "-o", s(&out_path)];
        args.extend_from_slice(extra);
        let out = tilepattern(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        aligned(&obj::read(&out_path).unwrap(), d)
    };
    let plain = remesh(&[], "plain.obj");
    let by_face = remesh(&["--field", s(&faces)], "faces.obj");
    let by_vertex = remesh(
        &["--field", s(&vertices), "--field-weight", "1"],
        "vertices.obj",
    );
    let none = remesh(&["--field", s(&faces), "--field-weight", "0"], "none.obj");
    eprintln!(
        "aligned with the field: plain {plain:.3}, per face {by_face:.3}, per vertex {by_vertex:.3}, weight 0 {none:.3}"
    );
    // Without a field the plate's corners hold the rows on its axes (0 % on the field);
    // with one the boundary is left to the field and 92 % of interior edges follow it.
    assert!(plain < 0.1, "{plain:.3}");
    assert!(none < 0.1, "{none:.3}");
    assert!(by_face > 0.85, "{by_face:.3}");
    assert!(by_vertex > 0.85, "{by_vertex:.3}");
}

#[test]
fn bad_field_files_name_what_is_wrong() {
    let dir = scratch("cli-field-bad");
    let n = 4;
    let surface = dir.join("plate.obj");
    std::fs::write(&surface, plate_obj(n)).unwrap();
    let run = |field: &str, extra: &[&str]| {
        let path = dir.join("field.csv");
        std::fs::write(&path, field).unwrap();
        let quads = dir.join("q.obj");
        let mut args = vec![
            "remesh",
            s(&surface),
            "--edge",
            "0.3",
            "-o",
            s(&quads),
            "--field",
            s(&path),
        ];
        args.extend_from_slice(extra);
        let out = tilepattern(&args);
        assert!(!out.status.success());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let good_row = "1,0,0\n";
    // 25 vertices, 32 faces: 7 vectors match neither.
    let err = run(&good_row.repeat(7), &[]);
    assert!(
        err.contains("7 vectors") && err.contains("25 vertices") && err.contains("32 faces"),
        "{err}"
    );
    let mut rows = good_row.repeat(25);
    rows = rows.replacen(
        "1,0,0\n1,0,0\n1,0,0\n1,0,0\n",
        "1,0,0\n1,0,0\n1,0,0\n0,0,0\n",
        1,
    );
    let err = run(&rows, &[]);
    assert!(err.contains("vertex 3"), "{err}");
    let err = run(&format!("{}NaN,1,0\n", good_row.repeat(31)), &[]);
    assert!(err.contains("face 31"), "{err}");
    let err = run(&format!("{}1,0\n", good_row.repeat(2)), &[]);
    assert!(err.contains("line 3"), "{err}");
    let err = run(&good_row.repeat(25), &["--field-weight", "1.5"]);
    assert!(err.contains("field weight 1.5"), "{err}");
    // A weight without a field is a usage error.
    let out = tilepattern(&[
        "remesh",
        s(&surface),
        "--edge",
        "0.3",
        "-o",
        "x.obj",
        "--field-weight",
        "0.5",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--field"));
}

#[test]
fn as_many_vertices_as_faces_reads_per_vertex_with_a_warning() {
    // A quad torus of 12 x 8 faces has 96 vertices and 96 faces.
    let dir = scratch("cli-field-torus");
    let (n, m) = (12, 8);
    let mut text = String::new();
    for j in 0..m {
        for i in 0..n {
            let (u, v) = (
                std::f64::consts::TAU * i as f64 / n as f64,
                std::f64::consts::TAU * j as f64 / m as f64,
            );
            let r = 2.0 + 0.8 * v.cos();
            text += &format!("v {} {} {}\n", r * u.cos(), r * u.sin(), 0.8 * v.sin());
        }
    }
    let at = |i: usize, j: usize| (i % n) + n * (j % m) + 1;
    for j in 0..m {
        for i in 0..n {
            text += &format!(
                "f {} {} {} {}\n",
                at(i, j),
                at(i + 1, j),
                at(i + 1, j + 1),
                at(i, j + 1)
            );
        }
    }
    let surface = dir.join("torus.obj");
    std::fs::write(&surface, text).unwrap();
    let field = dir.join("field.csv");
    std::fs::write(&field, "0,0,1\n".repeat(n * m)).unwrap();
    let quads = dir.join("q.obj");
    let out = tilepattern(&[
        "remesh",
        s(&surface),
        "--edge",
        "0.4",
        "-o",
        s(&quads),
        "--field",
        s(&field),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("as many vertices as faces (96)"), "{err}");
}

#[test]
fn a_field_counted_against_the_files_vertices_or_faces_is_read_after_welding() {
    // The plate as a triangle soup (every triangle with its own three vertices, as STL and
    // face-by-face exports give): welding joins them, and the designer's vectors, written
    // one per vertex or face of the file, still count.
    let dir = scratch("cli-field-soup");
    let n = 12;
    let plate = common::plate_obj(n);
    let points: Vec<&str> = plate.lines().filter(|l| l.starts_with("v ")).collect();
    let mut soup = String::new();
    let mut triangles = 0;
    for face in plate.lines().filter(|l| l.starts_with("f ")) {
        for id in face.split_whitespace().skip(1) {
            soup += points[id.parse::<usize>().unwrap() - 1];
            soup.push('\n');
        }
        soup += &format!(
            "f {} {} {}\n",
            3 * triangles + 1,
            3 * triangles + 2,
            3 * triangles + 3
        );
        triangles += 1;
    }
    let surface = dir.join("soup.obj");
    std::fs::write(&surface, soup).unwrap();
    let a = 30f64.to_radians();
    let d = Vector3::new(a.cos(), a.sin(), 0.0);
    let row = format!("{},{},0\n", d.x, d.y);
    let remesh = |rows: String, name: &str| {
        let field = dir.join(format!("{name}.csv"));
        std::fs::write(&field, rows).unwrap();
        let quads = dir.join(format!("{name}.obj"));
        let out = tilepattern(&[
            "remesh",
            s(&surface),
            "--edge",
            "0.145",
            "-o",
            s(&quads),
            "--field",
            s(&field),
        ]);
        (out, quads)
    };
    for (name, count) in [("per-vertex", 3 * triangles), ("per-face", triangles)] {
        let (out, quads) = remesh(row.repeat(count), name);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{name}: {err}");
        let share = aligned(&obj::read(&quads).unwrap(), d);
        assert!(share > 0.85, "{name}: {share:.3}");
    }
    // A bad vector is named by its number in the file.
    let rows = row.repeat(triangles - 1) + "0,0,0\n";
    let (out, _) = remesh(rows, "bad");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains(&format!("face {}", triangles - 1)), "{err}");
    let (out, _) = remesh(
        "0,0,0\n".to_owned() + &row.repeat(3 * triangles - 1),
        "bad-vertex",
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("vertex 0"), "{err}");
}
