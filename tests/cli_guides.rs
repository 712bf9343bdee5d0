//! `--guides FILE` and `--guide-weight` on the command line (issue 20): polylines the quad
//! rows follow; bad files are refused with the line, curve or point at fault.

mod common;

use common::{plate_obj, s, scratch, tilepattern};
use nalgebra::Vector3;
use tilepattern::mesh::{PolyMesh, obj};

/// Share of the edges of a flat quad mesh with their midpoint within `within` of the line
/// through (1, 1) along `d` that lie within 10 degrees of `d` or its perpendicular.
fn along(quads: &PolyMesh, d: Vector3<f64>, within: f64) -> f64 {
    let p = quads.positions();
    let centre = Vector3::new(1.0, 1.0, 0.0);
    let (mut near, mut good) = (0, 0);
    for face in quads.faces() {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            let mid = (p[a].coords + p[b].coords) * 0.5 - centre;
            if (mid - d * mid.dot(&d)).norm() > within {
                continue;
            }
            near += 1;
            let e = p[b].coords - p[a].coords;
            let angle = (e.dot(&d).abs() / e.norm()).min(1.0).acos().to_degrees();
            if angle.min(90.0 - angle) <= 10.0 {
                good += 1;
            }
        }
    }
    assert!(near > 30, "{near} edges near the guide");
    good as f64 / near as f64
}

#[test]
fn a_guides_file_as_text_or_json_turns_the_quads_near_it() {
    let dir = scratch("cli-guides");
    let surface = dir.join("plate.obj");
    std::fs::write(&surface, plate_obj(24)).unwrap();
    let a = 30f64.to_radians();
    let d = Vector3::new(a.cos(), a.sin(), 0.0);
    let point = |r: f64| format!("{} {} 0", 1.0 + r * d.x, 1.0 + r * d.y);
    // Text: the guide in three points (with a comment), and a short second curve near
    // the corner along the same direction.
    let text = dir.join("guides.txt");
    std::fs::write(
        &text,
        format!(
            "# a 30 degree line\n{}\n{}\n{}\n\n0.1 0.1 0\n{} {} 0\n",
            point(-1.1),
            point(0.0),
            point(1.1),
            0.1 + 0.3 * d.x,
            0.1 + 0.3 * d.y
        ),
    )
    .unwrap();
    let json = dir.join("guides.json");
    std::fs::write(
        &json,
        format!(
            "[[[{}, {}, 0], [{}, {}, 0]]]",
            1.0 - 1.1 * d.x,
            1.0 - 1.1 * d.y,
            1.0 + 1.1 * d.x,
            1.0 + 1.1 * d.y
        ),
    )
    .unwrap();
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
        along(&obj::read(&out_path).unwrap(), d, 0.145)
    };
    let plain = remesh(&[], "plain.obj");
    let by_text = remesh(&["--guides", s(&text)], "text.obj");
    let by_json = remesh(&["--guides", s(&json), "--guide-weight", "1"], "json.obj");
    let none = remesh(&["--guides", s(&json), "--guide-weight", "0"], "none.obj");
    eprintln!(
        "edges within t of the guide along it: plain {plain:.3}, text {by_text:.3}, JSON {by_json:.3}, weight 0 {none:.3}"
    );
    // Without guides the plate's corners hold the rows on its axes, 30 degrees off.
    assert!(plain < 0.1, "{plain:.3}");
    assert!(none < 0.1, "{none:.3}");
    assert!(by_text > 0.85, "{by_text:.3}");
    assert!(by_json > 0.85, "{by_json:.3}");
}

#[test]
fn bad_guides_files_name_what_is_wrong() {
    let dir = scratch("cli-guides-bad");
    let surface = dir.join("plate.obj");
    std::fs::write(&surface, plate_obj(4)).unwrap();
    let run = |guides: &str, extra: &[&str]| {
        let path = dir.join("guides.txt");
        std::fs::write(&path, guides).unwrap();
        let quads = dir.join("q.obj");
        let mut args = vec![
            "remesh",
            s(&surface),
            "--edge",
            "0.3",
            "-o",
            s(&quads),
            "--guides",
            s(&path),
        ];
        args.extend_from_slice(extra);
        let out = tilepattern(&args);
        assert!(!out.status.success());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let good = "0 0 0\n2 2 0\n";
    let err = run(&format!("{good}\n1 1 0\n"), &[]);
    assert!(err.contains("guide curve 1 has 1 point"), "{err}");
    let err = run(&format!("{good}\n0 0 0\nNaN 1 0\n"), &[]);
    assert!(err.contains("point 1 of guide curve 1"), "{err}");
    let err = run("1 1 0\n1 1 0\n", &[]);
    assert!(err.contains("guide curve 0 has no length"), "{err}");
    let err = run(&format!("{good}\n0 0 5\n2 2 5\n"), &[]);
    assert!(err.contains("guide curve 1 is nowhere near"), "{err}");
    let err = run("0 0 0\n1 1\n", &[]);
    assert!(err.contains("line 2"), "{err}");
    // Half of a curve drawn past the plate's edge: a warning, and the remesh goes on.
    let path = dir.join("past.txt");
    std::fs::write(&path, "1 0.2 0\n1 2.6 0\n1 5 0\n").unwrap();
    let quads = dir.join("past.obj");
    let out = tilepattern(&[
        "remesh",
        s(&surface),
        "--edge",
        "0.3",
        "-o",
        s(&quads),
        "--guides",
        s(&path),
    ]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: guide curve 0") && stderr.contains("50 % of its length"),
        "{stderr}"
    );
    let err = run(good, &["--guide-weight", "1.5"]);
    assert!(err.contains("guide weight 1.5"), "{err}");
    // A weight without guides is a usage error.
    let out = tilepattern(&[
        "remesh",
        s(&surface),
        "--edge",
        "0.3",
        "-o",
        "x.obj",
        "--guide-weight",
        "0.5",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--guides"));
}
