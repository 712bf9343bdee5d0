//! The `tilepattern` command line: files written, JSON contract, errors a designer can act on.

mod common;

use common::{json, s, scratch, tilepattern, tilepattern_on_threads};

#[test]
fn demo_writes_the_four_files() {
    let dir = scratch("demo");
    let out = tilepattern(&["demo", "--out", s(&dir), "--span", "1.5"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in ["quads.obj", "tiles.obj", "report.json", "pattern.svg"] {
        assert!(dir.join(file).is_file(), "{file} missing");
    }
    let report = json(&dir.join("report.json"));
    assert_eq!(report["status"], "optimal");
    assert_eq!(report["units"], "m");
    assert!(report["full_tiles"].as_u64().unwrap() > 0);
    assert!(
        std::fs::read_to_string(dir.join("pattern.svg"))
            .unwrap()
            .starts_with("<svg")
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("full tiles"));
}

#[test]
fn match_then_tiles_round_trip_with_stable_fields() {
    let dir = scratch("match");
    assert!(
        tilepattern(&["demo", "--out", s(&dir), "--span", "1.5"])
            .status
            .success()
    );
    let quads = dir.join("quads.obj");
    let pairs = dir.join("pairs.json");
    let out = tilepattern(&[
        "match",
        s(&quads),
        "--pattern",
        "staggered",
        "--weight",
        "2",
        "--time-limit",
        "30",
        "--json",
        s(&pairs),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let found = json(&pairs);
    for field in [
        "faces",
        "pairs",
        "unpaired",
        "continuous_joints",
        "shifted_pairs",
        "objective",
        "bound",
        "status",
        "seconds",
    ] {
        assert!(found.get(field).is_some(), "field {field} missing");
    }
    assert_eq!(found["continuous_joints"], 0);

    let tiles = dir.join("tiles.obj");
    let report = dir.join("report.json");
    let svg = dir.join("p.svg");
    // The paper's placement (section 3.5): every pair is a full tile on the quads.
    let out = tilepattern(&[
        "tiles",
        s(&quads),
        "--pairs",
        s(&pairs),
        "--tile",
        "280x140x15",
        "--joint",
        "10",
        "--no-fit",
        "-o",
        s(&tiles),
        "--json",
        s(&report),
        "--svg",
        s(&svg),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let paper = json(&report);
    let paired = found["pairs"].as_array().unwrap().len() as u64;
    // The report embeds the pattern it tiled, every field of it but the pairs themselves
    // (counted), bound_source included.
    let embedded = &paper["pattern"];
    assert_eq!(embedded["pairs"].as_u64().unwrap(), paired);
    assert_eq!(
        embedded["unpaired"].as_u64().unwrap(),
        found["unpaired"].as_array().unwrap().len() as u64
    );
    for field in [
        "faces",
        "continuous_joints",
        "shifted_pairs",
        "objective",
        "bound",
        "gap",
        "status",
        "bound_source",
    ] {
        assert!(
            found.get(field).is_some(),
            "field {field} missing from the pairs"
        );
        assert_eq!(embedded[field], found[field], "report's pattern.{field}");
    }
    assert_eq!(paper["objective"], embedded["objective"]);
    assert_eq!(paper["full_tiles"].as_u64().unwrap(), paired);
    assert_eq!(paper["tile"]["length"], 0.28);
    assert!(svg.is_file() && tiles.is_file());
    assert!(paper.get("fit").is_none() && paper["joints"].get("before_fit").is_none());

    // The fit (default): the report gives the joints before and after, and what the fit did.
    let out = tilepattern(&[
        "tiles",
        s(&quads),
        "--pairs",
        s(&pairs),
        "--tile",
        "280x140x15",
        "--joint",
        "10",
        "-o",
        s(&tiles),
        "--json",
        s(&report),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("after the fit"));
    let fitted = json(&report);
    for field in [
        "contacts",
        "overlaps",
        "max_overlap",
        "p95_deviation",
        "within_2mm",
        "within_5mm",
        "max_gap",
        "fit_cuts",
        "before_fit",
    ] {
        assert!(
            fitted["joints"].get(field).is_some(),
            "joints.{field} missing"
        );
    }
    for field in [
        "status",
        "iterations",
        "objective_before",
        "objective_after",
        "mean_move",
        "max_move",
    ] {
        assert!(fitted["fit"].get(field).is_some(), "fit.{field} missing");
    }
    assert_eq!(
        fitted["joints"]["before_fit"]["p95_deviation"],
        paper["joints"]["p95_deviation"]
    );
    assert!(
        fitted["joints"]["p95_deviation"].as_f64().unwrap()
            < paper["joints"]["p95_deviation"].as_f64().unwrap()
    );
}

#[test]
fn same_input_gives_byte_identical_json_apart_from_timings() {
    let dir = scratch("determinism");
    assert!(
        tilepattern(&["demo", "--out", s(&dir), "--span", "0.7"])
            .status
            .success()
    );
    let quads = dir.join("quads.obj");
    let run = |name: &str| {
        let path = dir.join(name);
        for pattern in ["stack", "staggered", "running-bond"] {
            assert!(
                tilepattern(&["match", s(&quads), "--pattern", pattern, "--json", s(&path)])
                    .status
                    .success()
            );
        }
        let text = std::fs::read_to_string(&path).unwrap();
        text.lines()
            .filter(|l| !l.contains("\"seconds\""))
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(run("a.json"), run("b.json"));
}

#[test]
fn errors_say_what_is_wrong_and_exit_non_zero() {
    let dir = scratch("errors");
    let missing = tilepattern(&["match", "/nonexistent/shell.obj"]);
    assert!(!missing.status.success());
    assert!(String::from_utf8_lossy(&missing.stderr).contains("/nonexistent/shell.obj"));

    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 2 9\n").unwrap();
    let out = tilepattern(&["match", s(&bad)]);
    assert!(!out.status.success());
    let message = String::from_utf8_lossy(&out.stderr);
    assert!(message.contains("face 1 refers to vertex 8"), "{message}");

    let out = tilepattern(&[
        "tiles",
        s(&bad),
        "--pairs",
        "x.json",
        "--tile",
        "280x140",
        "-o",
        "t.obj",
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("length x width x thickness"));

    let out = tilepattern(&["demo", "--out", s(&dir), "--weight=-1"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("bond weight -1"));

    let out = tilepattern(&["demo", "--out", s(&dir), "--gap", "2"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("relative gap 2"));
}

#[test]
fn match_stops_at_the_gap_it_is_given() {
    // A 10 x 10 grid of unit quads: the paper's plain program on CBC would prove it only by
    // branching; with --gap 0.05 it stops at the first pattern within 5 % of its bound.
    let dir = scratch("gap");
    let quads = dir.join("grid.obj");
    std::fs::write(&quads, grid_obj(10)).unwrap();
    let pairs = dir.join("pairs.json");
    let out = tilepattern(&[
        "match",
        s(&quads),
        "--method",
        "mip",
        "--formulation",
        "paper",
        "--time-limit",
        "60",
        "--gap",
        "0.05",
        "--json",
        s(&pairs),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let found = json(&pairs);
    assert_eq!(found["status"], "feasible");
    let gap = found["gap"].as_f64().unwrap();
    assert!(gap > 0.0 && gap <= 0.05, "gap {gap}");
}

#[test]
fn the_log_shows_the_search_when_standard_error_is_no_terminal() {
    let dir = scratch("log");
    let quads = dir.join("grid.obj");
    std::fs::write(&quads, grid_obj(12)).unwrap();
    let args = |log: bool| {
        let mut a = vec!["match", s(&quads)];
        if log {
            a.push("--log");
        }
        a
    };
    // Standard error is a pipe here: without --log no progress is written.
    let quiet = tilepattern(&args(false));
    assert!(quiet.status.success());
    let quiet = String::from_utf8_lossy(&quiet.stderr);
    assert!(!quiet.contains("pattern "), "{quiet}");
    let logged = tilepattern(&args(true));
    assert!(logged.status.success());
    let log = String::from_utf8_lossy(&logged.stderr);
    let lines: Vec<&str> = log.lines().filter(|l| l.starts_with("pattern ")).collect();
    assert!(!lines.is_empty(), "{log}");
    // The last line has the proven optimum of the 12 x 12 grid: 72 tiles, one joint.
    let last = lines.last().unwrap();
    assert!(last.contains("best 71.5  bound 71.5  gap 0.00 %"), "{log}");
    assert!(!log.contains('\r'), "lines, not a redrawn line: {log:?}");
    // The result on standard output either way.
    let result: serde_json::Value = serde_json::from_slice(&logged.stdout).unwrap();
    assert_eq!(result["objective"], 71.5);
}

/// An `n` x `n` grid of unit quads, as OBJ text.
fn grid_obj(n: usize) -> String {
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            text += &format!("v {i} {j} 0\n");
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = |i: usize, j: usize| j * (n + 1) + i + 1;
            text += &format!(
                "f {} {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            );
        }
    }
    text
}

/// A triangulated saddle z = (x^2 - y^2) / 4 over [-1, 1]^2, as OBJ text.
/// `run SURFACE --tile 280x140x15 --joint 10 --out OUT`.
fn run_args<'a>(surface: &'a std::path::Path, out: &'a std::path::Path) -> Vec<&'a str> {
    vec![
        "run",
        s(surface),
        "--tile",
        "280x140x15",
        "--joint",
        "10",
        "--out",
        s(out),
    ]
}

fn saddle_obj() -> String {
    saddle_obj_of(24)
}

/// [`saddle_obj`] on an `n` x `n` grid.
fn saddle_obj_of(n: usize) -> String {
    let mut text = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (
                -1.0 + 2.0 * i as f64 / n as f64,
                -1.0 + 2.0 * j as f64 / n as f64,
            );
            text += &format!("v {x} {y} {}\n", (x * x - y * y) / 4.0);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let v = |i: usize, j: usize| i + (n + 1) * j + 1;
            text += &format!(
                "f {} {} {}\nf {} {} {}\n",
                v(i, j),
                v(i + 1, j),
                v(i + 1, j + 1),
                v(i, j),
                v(i + 1, j + 1),
                v(i, j + 1)
            );
        }
    }
    text
}

#[test]
fn remesh_gives_the_same_quads_on_one_thread_and_on_several() {
    // Quads of 30 mm on a 2 m saddle: the working surface has over 100,000 edges, so the
    // conjugate gradients split their loops into parts (`parallel`), which must not change
    // a bit of the result whatever the number of threads.
    let dir = scratch("threads");
    let surface = dir.join("saddle.obj");
    std::fs::write(&surface, saddle_obj_of(48)).unwrap();
    let quads = |threads: &str| {
        let quads = dir.join(format!("quads-{threads}.obj"));
        tilepattern_on_threads(
            threads,
            &["remesh", s(&surface), "--edge", "0.03", "-o", s(&quads)],
        );
        std::fs::read(&quads).unwrap()
    };
    let one = quads("1");
    assert!(one.len() > 100_000, "{} bytes", one.len());
    assert!(one == quads("2"));
    assert!(one == quads("3"));
}

#[test]
fn run_gives_the_same_tiles_and_report_on_one_thread_and_on_several() {
    // A 2 m saddle of 4608 triangles: the curvature fits, the remesh metrics, the tear fill's
    // samples and the report's coverage go over more than a thousand items each, so they are
    // split over the threads (`parallel::map`), which must not change a bit of the tiles or
    // of the report (its timings aside).
    let dir = scratch("run-threads");
    let surface = dir.join("saddle.obj");
    std::fs::write(&surface, saddle_obj_of(48)).unwrap();
    let run = |threads: &str| {
        let out_dir = dir.join(format!("out-{threads}"));
        tilepattern_on_threads(threads, &run_args(&surface, &out_dir));
        let mut report = json(&out_dir.join("report.json"));
        fn drop_seconds(value: &mut serde_json::Value) {
            match value {
                serde_json::Value::Object(map) => {
                    map.remove("seconds");
                    map.values_mut().for_each(drop_seconds);
                }
                serde_json::Value::Array(items) => items.iter_mut().for_each(drop_seconds),
                _ => {}
            }
        }
        drop_seconds(&mut report);
        (std::fs::read(out_dir.join("tiles.obj")).unwrap(), report)
    };
    let (tiles, report) = run("1");
    assert!(
        report["joints"]["contacts"].as_u64().unwrap() > 100,
        "{report}"
    );
    assert!(
        report["cutting"]["coverage"].as_f64().unwrap() > 0.9,
        "{report}"
    );
    for threads in ["2", "3"] {
        let (other_tiles, other_report) = run(threads);
        assert!(
            tiles == other_tiles,
            "tiles.obj differs on {threads} threads"
        );
        assert_eq!(
            report, other_report,
            "report.json differs on {threads} threads"
        );
    }
}

#[test]
fn remesh_and_run_go_from_triangles_to_tiles() {
    let dir = scratch("run");
    let surface = dir.join("saddle.obj");
    std::fs::write(&surface, saddle_obj()).unwrap();

    let quads = dir.join("quads.obj");
    let metrics = dir.join("metrics.json");
    let out = tilepattern(&[
        "remesh",
        s(&surface),
        "--edge",
        "0.145",
        "-o",
        s(&quads),
        "--json",
        s(&metrics),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let m = json(&metrics);
    assert_eq!(m["pure_quad"], true);
    for field in [
        "faces",
        "interior_irregular_vertices",
        "boundary_vertices_off_input",
        "mean_edge_ratio",
        "edges_within_20pct",
        "faces_area_within_20pct",
        "p95_corner_angle_deviation_deg",
        "max_distance_to_input_ratio",
        "area_covered_ratio",
        "seconds",
    ] {
        assert!(m.get(field).is_some(), "metrics field {field} missing");
    }

    let run_dir = dir.join("out");
    let out = tilepattern(&[
        "run",
        s(&surface),
        "--tile",
        "280x140x15",
        "--joint",
        "10",
        "--pattern",
        "staggered",
        "--time-limit",
        "20",
        "--out",
        s(&run_dir),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in ["quads.obj", "tiles.obj", "report.json", "pattern.svg"] {
        assert!(run_dir.join(file).is_file(), "{file} missing");
    }
    let report = json(&run_dir.join("report.json"));
    assert_eq!(report["units"], "m");
    assert!(report["remesh"]["faces"].as_u64().unwrap() > 100);
    assert!(report["full_tiles"].as_u64().unwrap() > 50);
    // The laying-order line (on standard output) gives the report's count of tiles climbing
    // the slopes, when there are sloped tiles at all.
    let said = String::from_utf8_lossy(&out.stdout);
    let sequence = &report["sequence"];
    let sloped = sequence["sloped_tiles"].as_u64().unwrap();
    let climbing = sequence["climbing_tiles"].as_u64().unwrap();
    assert!(climbing <= sloped);
    if sloped > 0 {
        assert!(
            said.contains(&format!(
                "{climbing} of the {sloped} whole tiles on slopes over 20 degrees run up them"
            )),
            "{said}"
        );
    } else {
        assert!(!said.contains("whole tiles on slopes"), "{said}");
    }

    let bad = tilepattern(&["remesh", s(&surface), "--edge", "0", "-o", s(&quads)]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("target edge 0"));
}

#[test]
fn run_tries_six_quad_meshes_and_says_which_tiles_it_kept() {
    let dir = scratch("run-tries");
    let surface = dir.join("saddle.obj");
    std::fs::write(&surface, saddle_obj()).unwrap();
    let run = |extra: &[&str], out_dir: &std::path::Path| {
        let mut args = run_args(&surface, out_dir);
        args.extend_from_slice(extra);
        tilepattern(&args)
    };
    let auto = dir.join("auto");
    let out = run(&[], &auto);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report = json(&auto.join("report.json"));
    let tries = report["tries"].as_array().expect("tries listed");
    assert_eq!(tries.len(), 6, "{report}");
    // The curvature field, the smooth field, then the curvature field at two more strengths,
    // then the smooth field's quads laid out for the level courses (written for it alone),
    // then the smooth field free of the saddle's square boundary, which the first follows.
    let fields: Vec<&str> = tries.iter().map(|t| t["field"].as_str().unwrap()).collect();
    assert_eq!(
        fields,
        [
            "curvature",
            "smooth",
            "curvature",
            "curvature",
            "smooth",
            "smooth"
        ]
    );
    let flag = |key: &str| -> Vec<bool> {
        tries
            .iter()
            .map(|t| t.get(key).is_some_and(|a| a == true))
            .collect()
    };
    assert_eq!(
        flag("quads_along_courses"),
        [false, false, false, false, true, false]
    );
    assert_eq!(
        flag("boundary_free"),
        [false, false, false, false, false, true]
    );
    assert_eq!(report["remesh"]["aligned_boundary"], true, "{report}");
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(printed.contains("quads along the courses") && printed.contains("boundary free"));
    let chosen = report["chosen_try"].as_u64().unwrap() as usize;
    let rank = |t: &serde_json::Value| {
        (
            t["wide_joints"].as_bool().unwrap(),
            t["fit_cuts"].as_bool().unwrap(),
            t["score"].as_f64().unwrap(),
        )
    };
    assert!(
        tries.iter().all(|t| rank(t) >= rank(&tries[chosen])),
        "{tries:?}"
    );
    for field in [
        "renormalisation",
        "field",
        "quads",
        "interior_irregular_vertices",
        "p95_deviation",
        "cut_share",
        "coverage",
        "wide_joints",
        "fit_cuts",
        "score",
        "seconds",
    ] {
        assert!(tries[0].get(field).is_some(), "tries field {field} missing");
    }
    assert_eq!(
        tries[chosen]["quads"].as_u64(),
        report["remesh"]["faces"].as_u64()
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("<- kept"));

    let one = dir.join("one");
    assert!(run(&["--tries", "1"], &one).status.success());
    let report = json(&one.join("report.json"));
    assert!(report.get("tries").is_none() && report.get("chosen_try").is_none());

    let bad = run(&["--tries", "7"], &dir.join("bad"));
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--tries"));
    // Each try's `key` in the report of a run with `extra` options.
    let listed = |extra: &[&str], key: &str| -> Vec<serde_json::Value> {
        let out_dir = dir.join(extra.join("_"));
        assert!(run(extra, &out_dir).status.success());
        let report = json(&out_dir.join("report.json"));
        let tries = report["tries"].as_array().unwrap();
        tries.iter().map(|t| t[key].clone()).collect()
    };
    // The tries start from --renormalisation: the smooth field at it, then twice and half,
    // then the smooth field's quads along the courses at it, and free of the boundary.
    assert_eq!(
        listed(&["--renormalisation", "0.3"], "renormalisation"),
        [0.3, 0.3, 0.6, 0.15, 0.3, 0.3]
    );
    // --smooth asks for the smooth field: every try has it, and no smooth try of its own is
    // added (nor its quads along the courses).
    assert_eq!(listed(&["--smooth"], "field"), ["smooth"; 3]);
    // With a direction asked for, no smooth try: what the designer asked is kept.
    assert_eq!(listed(&["--direction", "1,0,0"], "field"), ["direction"; 3]);
    let bad = run(&["--renormalisation", "-1"], &dir.join("bad"));
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("renormalisation"));
}
