//! `--zones FILE` on the command line (issue 20): a bond per face, as text lines or JSON, for
//! `match` (faces of the quad mesh) and `run` (faces of the input surface, carried over to the
//! quads); bad files are refused with the line, key or face at fault.

mod common;

use common::{json, s, scratch, tilepattern};
use tilepattern::mesh::{generate, obj};

/// A flat grid of `n` x `n` quads of 0.145 (a 280 mm tile's half plus a joint, in metres).
fn grid_obj(dir: &std::path::Path, n: usize) -> std::path::PathBuf {
    let path = dir.join("grid.obj");
    let grid = generate::grid(n, n);
    let scaled = tilepattern::mesh::PolyMesh::new(
        grid.positions().iter().map(|p| p * 0.145).collect(),
        grid.faces().to_vec(),
    )
    .unwrap();
    obj::write(&scaled, &path).unwrap();
    path
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// `match` with zones from `zones`, its JSON.
fn match_with(
    quads: &std::path::Path,
    zones: &std::path::Path,
    json_out: &std::path::Path,
) -> serde_json::Value {
    let out = tilepattern(&[
        "match",
        s(quads),
        "--zones",
        s(zones),
        "--time-limit",
        "5",
        "--json",
        s(json_out),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    json(json_out)
}

#[test]
fn match_reads_zones_as_text_or_json_and_reports_faces_per_bond() {
    let dir = scratch("cli-zones-match");
    let quads = grid_obj(&dir, 8);
    // Rows 3 and 4 (faces 24 to 39) herringbone, face 0 stack, the rest --pattern.
    let text = dir.join("zones.txt");
    std::fs::write(&text, "# a band\n24-39 herringbone\n0,stack   # a corner\n").unwrap();
    let object = dir.join("zones.json");
    std::fs::write(
        &object,
        r#"{"0": "stack", "24-31": "herringbone", "32-39": "herringbone", "5": null}"#,
    )
    .unwrap();
    let array = dir.join("array.json");
    let items: Vec<&str> = (0..64)
        .map(|f| match f {
            0 => "\"stack\"",
            24..=39 => "\"herringbone\"",
            _ => "null",
        })
        .collect();
    std::fs::write(&array, format!("[{}]", items.join(", "))).unwrap();

    let found: Vec<serde_json::Value> = [&text, &object, &array]
        .iter()
        .enumerate()
        .map(|(k, zones)| match_with(&quads, zones, &dir.join(format!("m{k}.json"))))
        .collect();
    for f in &found {
        assert_eq!(f["zones"]["herringbone"], 16, "{f}");
        assert_eq!(f["zones"]["stack"], 1);
        assert_eq!(f["zones"]["staggered"], 47);
        assert_eq!(f["faces"], 64);
        // The same options whatever the file's format: the same pattern.
        assert_eq!(f["pairs"], found[0]["pairs"]);
        assert_eq!(f["objective"], found[0]["objective"]);
    }
    // Without --zones the JSON has no zones field.
    let plain = dir.join("plain.json");
    let out = tilepattern(&["match", s(&quads), "--time-limit", "5", "--json", s(&plain)]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(json(&plain).get("zones").is_none());

    // `tiles` reads match's JSON with zones back.
    let out = tilepattern(&[
        "tiles",
        s(&quads),
        "--pairs",
        s(&dir.join("m0.json")),
        "--tile",
        "280x140x15",
        "--units",
        "m",
        "--output",
        s(&dir.join("tiles.obj")),
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

#[test]
fn bad_zones_files_name_the_line_the_face_or_the_count() {
    let dir = scratch("cli-zones-bad");
    let quads = grid_obj(&dir, 4);
    let cases: [(&str, &str, &[&str]); 7] = [
        (
            "0-3 staggered\n4 herringbon\n",
            "typo.txt",
            &["line 2", "'herringbon' is not a bond", "basket-weave"],
        ),
        (
            "16 stack\n",
            "range.txt",
            &["line 1", "face 16 is out of range", "16 faces (0 to 15)"],
        ),
        (
            "3 stack running-bond\n",
            "malformed.txt",
            &["line 1", "FACE BOND or FIRST-LAST BOND"],
        ),
        (
            "[\"stack\", null]",
            "short.json",
            &["2 zones for a quad mesh of 16 faces"],
        ),
        (
            "{\"2\": \"zigzag\"}",
            "key.json",
            &["key \"2\"", "'zigzag' is not a bond"],
        ),
        (
            "0-5 stack\n5 herringbone\n",
            "twice.txt",
            &["line 2", "face 5", "line 1"],
        ),
        ("# only a comment\n", "empty.txt", &["no zones found"]),
    ];
    for (content, name, words) in cases {
        let path = dir.join(name);
        std::fs::write(&path, content).unwrap();
        let out = tilepattern(&["match", s(&quads), "--zones", s(&path)]);
        let err = stderr(&out);
        assert!(!out.status.success(), "{name}");
        assert!(err.contains(name), "{name}: {err}");
        for w in words {
            assert!(err.contains(w), "{name}: '{w}' missing in {err}");
        }
    }
    let out = tilepattern(&["match", s(&quads), "--zones", s(&dir.join("missing.txt"))]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("cannot read the zones file"),
        "{}",
        stderr(&out)
    );
    // A herringbone zone cannot lie in level courses.
    let band = dir.join("band.txt");
    std::fs::write(&band, "4-7 herringbone\n").unwrap();
    let out = tilepattern(&[
        "match",
        s(&quads),
        "--zones",
        s(&band),
        "--courses",
        "level",
    ]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("herringbone") && stderr(&out).contains("courses free"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn run_carries_the_surface_zones_over_to_the_quads() {
    let dir = scratch("cli-zones-run");
    // A flat 1.74 m plate of 12 x 12 squares, each two triangles (face 2 (i + 12 j) and the
    // next lie in column i): the columns 4 to 7 (x from 0.58 to 1.16 m) are a herringbone band.
    let n = 12;
    let plate = generate::triangulate_quads(&generate::grid(n, n));
    let plate = tilepattern::mesh::PolyMesh::new(
        plate.positions().iter().map(|p| p * 0.145).collect(),
        plate.faces().to_vec(),
    )
    .unwrap();
    let surface = dir.join("plate.obj");
    obj::write(&plate, &surface).unwrap();
    let mut lines = String::new();
    for j in 0..n {
        let first = 2 * (4 + n * j);
        lines += &format!("{first}-{} herringbone\n", first + 7);
    }
    let zones = dir.join("zones.txt");
    std::fs::write(&zones, lines).unwrap();
    let out_dir = dir.join("out");
    let out = tilepattern(&[
        "run",
        s(&surface),
        "--tile",
        "280x140x15",
        "--units",
        "m",
        "--zones",
        s(&zones),
        "--time-limit",
        "5",
        "--out",
        s(&out_dir),
    ]);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    // The default level courses cannot hold a herringbone zone: free courses, said so.
    assert!(
        err.contains("herringbone lays tiles both ways: courses free"),
        "{err}"
    );

    let quads = obj::read(&out_dir.join("quads.obj")).unwrap();
    let report = json(&out_dir.join("report.json"));
    let counts = report["zones"].as_object().expect("report.json has zones");
    let total: u64 = counts.values().map(|v| v.as_u64().unwrap()).sum();
    assert_eq!(total as usize, quads.face_count());
    assert!(
        counts["herringbone"].as_u64().unwrap() > 0 && counts["staggered"].as_u64().unwrap() > 0
    );

    // zones.txt: each quad's zone, the zone of the triangle under its centroid.
    let written = std::fs::read_to_string(out_dir.join("zones.txt")).unwrap();
    let mut herringbone = vec![false; quads.face_count()];
    for line in written.lines().filter(|l| !l.starts_with('#')) {
        let (faces, bond) = line.split_once(' ').unwrap();
        let (a, b) = faces.split_once('-').unwrap_or((faces, faces));
        let (a, b): (usize, usize) = (a.parse().unwrap(), b.parse().unwrap());
        herringbone[a..=b].fill(bond == "herringbone");
    }
    for (q, &h) in herringbone.iter().enumerate() {
        let x = quads.face_centroid(q).x;
        let in_band = (0.58..1.16).contains(&x);
        // Centroids on the band's edge may go either way.
        if (x - 0.58).abs() > 1e-6 && (x - 1.16).abs() > 1e-6 {
            assert_eq!(h, in_band, "quad {q} at x = {x}");
        }
    }
    // The written zones feed `match` on the written quads.
    let again = match_with(
        &out_dir.join("quads.obj"),
        &out_dir.join("zones.txt"),
        &dir.join("again.json"),
    );
    assert_eq!(again["zones"], report["zones"]);

    // Zones are counted against the input surface's faces.
    let quad_count = dir.join("wrong.txt");
    std::fs::write(&quad_count, format!("{} stack\n", plate.face_count())).unwrap();
    let out = tilepattern(&[
        "run",
        s(&surface),
        "--tile",
        "280x140x15",
        "--units",
        "m",
        "--zones",
        s(&quad_count),
        "--out",
        s(&out_dir),
    ]);
    assert!(!out.status.success());
    assert!(
        stderr(&out).contains("the input surface has 288 faces"),
        "{}",
        stderr(&out)
    );
}
