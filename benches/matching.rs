//! Matching benchmark (issue: certified matching): the staggered model (eq. 2, w = 0.5) on
//! the paper-size ladder of n x n grids, the QuadriFlow meshes in `../shared/surfaces/quads/`,
//! the remesher's own quads of the shared surfaces (t = 0.14 m) and a 100k-face shell (the
//! dome remeshed at t = 0.038 m). Every mesh is solved by the default engine with a 1 s
//! limit (30 s for the 100k shell), by the default engine with the long limit, and by the
//! paper's whole program on CBC with the long limit, in one run. Writes a markdown table to
//! stdout and to `target/bench/matching.md`, with the speed-up over the paper's program at
//! the largest mesh that program proves.
//!
//! `cargo bench --bench matching` (all rows), or with arguments to pick rows, e.g.
//! `cargo bench --bench matching -- grid10 hypar`. `TP_BENCH_LIMIT` sets the long limit in
//! seconds (default 20).
//!
//! Every solve runs in a child process of its own (this program, called with `--solve`), so
//! that a CBC call that outlives its time limit (CBC cannot be stopped while Clp solves the
//! root LP) cannot hold up the next solve, and so that the peak memory reported is the
//! solve's own (the child's resident high-water mark, Linux only).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use tilepattern::mesh::{PolyMesh, generate, obj};
use tilepattern::pattern::{self, Bond, Formulation, Method, Pattern, PatternOptions, SolveStatus};
use tilepattern::remesh::{RemeshOptions, remesh};

/// Faces from which a mesh counts as large: its short run gets the large-mesh limit.
const LARGE: usize = 50_000;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--solve") {
        solve_one(&args[1..]);
        return;
    }
    let limit: f64 = std::env::var("TP_BENCH_LIMIT")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20.0);
    let wanted: Vec<String> = args.into_iter().filter(|a| !a.starts_with('-')).collect();
    let picked = |name: &str| wanted.is_empty() || wanted.iter().any(|w| name.contains(w.as_str()));
    let mut cases: Vec<(String, PolyMesh)> = [10, 14, 17, 24, 41, 100]
        .iter()
        .map(|&n| (format!("grid{n}"), generate::grid(n, n)))
        .filter(|(name, _)| picked(name))
        .collect();
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/surfaces");
    for name in ["hypar", "tubemesh", "vault", "dome"] {
        if picked(&format!("quadriflow-{name}")) {
            if let Ok(mesh) = obj::read(&shared.join(format!("quads/{name}.obj"))) {
                cases.push((format!("quadriflow-{name}"), mesh));
            }
        }
    }
    for (name, edge) in [
        ("hypar", 0.14),
        ("tubemesh", 0.14),
        ("vault", 0.14),
        ("dome", 0.14),
        ("dome", 0.038),
    ] {
        let label = if edge == 0.14 {
            format!("remeshed-{name}")
        } else {
            format!("remeshed-{name}-{edge}")
        };
        if !picked(&label) {
            continue;
        }
        let Ok(surface) = obj::read(&shared.join(format!("{name}.obj"))) else {
            continue;
        };
        let options = {
            let mut o = RemeshOptions::default();
            o.target_edge = edge;
            o.time_limit = Duration::from_secs(600);
            o
        };
        match remesh(&surface, &options) {
            Ok(remeshed) => cases.push((label, remeshed.quads)),
            Err(e) => eprintln!("{label}: remesh failed: {e}"),
        }
    }
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/bench");
    std::fs::create_dir_all(out.join("meshes")).expect("target is writable");

    let header = "| mesh | faces | method | limit s | seconds | status | objective | bound | gap % | bound from | peak MB |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    let mut table = header.to_string();
    println!("staggered w = 0.5; long limit {limit} s\n");
    print!("{header}");
    let mut speedups = Vec::new();
    for (name, mesh) in &cases {
        let short = if mesh.face_count() >= LARGE {
            30.0
        } else {
            1.0
        };
        let runs = [
            ("auto", "auto", short),
            ("auto", "auto", limit),
            ("paper MIP (CBC)", "paper", limit),
        ];
        let path = out.join("meshes").join(format!("{name}.obj"));
        obj::write(mesh, &path).expect("target is writable");
        let mut results: Vec<Pattern> = Vec::new();
        for (label, method, seconds) in runs {
            let child = std::process::Command::new(
                std::env::current_exe().expect("the bench knows itself"),
            )
            .args([
                "--solve",
                &path.display().to_string(),
                method,
                &seconds.to_string(),
            ])
            .output()
            .expect("the bench can start itself");
            let text = String::from_utf8_lossy(&child.stdout);
            let mut lines = text.lines();
            let found: Pattern = serde_json::from_str(lines.next().unwrap_or_default())
                .unwrap_or_else(|e| {
                    panic!(
                        "{name} {label}: {e}: {}",
                        String::from_utf8_lossy(&child.stderr)
                    )
                });
            let peak = lines.next().unwrap_or("-").to_string();
            let row = format!(
                "| {name} | {} | {label} | {seconds} | {:.2} | {:?} | {} | {:.1} | {:.2} | {:?} | {peak} |\n",
                mesh.face_count(),
                found.seconds,
                found.status,
                found.objective,
                found.bound,
                100.0 * found.gap,
                found.bound_source,
            );
            print!("{row}");
            table.push_str(&row);
            results.push(found);
        }
        // Speed-up at equal results: the paper's program proved its optimum, and the engine
        // (short or long run, the faster that reached it) proved the same.
        let paper = &results[2];
        if paper.status == SolveStatus::Optimal {
            let engine = results[..2]
                .iter()
                .filter(|r| r.status == SolveStatus::Optimal && r.objective == paper.objective)
                .map(|r| r.seconds)
                .fold(f64::INFINITY, f64::min);
            if engine.is_finite() {
                speedups.push((name.clone(), mesh.face_count(), paper.seconds, engine));
            }
        }
    }
    let mut summary = String::new();
    if let Some((name, faces, paper, engine)) = speedups.iter().max_by_key(|s| s.1) {
        let _ = writeln!(
            summary,
            "\nLargest mesh the paper's program proves within {limit} s: {name} ({faces} faces), {paper:.2} s; the engine proves the same optimum in {engine:.3} s: {:.0}x faster.",
            paper / engine.max(1e-3)
        );
    }
    print!("{summary}");
    let text = format!(
        "Staggered matching (eq. 2, w = 0.5); short limit 1 s (30 s from {LARGE} faces), long limit {limit} s.\n\n{table}{summary}"
    );
    std::fs::write(out.join("matching.md"), text).expect("target is writable");
}

/// The child's side: `--solve MESH.obj auto|paper SECONDS` solves the staggered program and
/// prints the pattern as one JSON line, then its peak resident memory in MB (or `-`).
fn solve_one(args: &[String]) {
    let mesh = obj::read(Path::new(&args[0])).expect("the bench wrote this mesh");
    let (method, formulation) = if args[1] == "paper" {
        (Method::Mip, Formulation::Paper)
    } else {
        (Method::Auto, Formulation::Strengthened)
    };
    let seconds: f64 = args[2].parse().expect("a number of seconds");
    let options = {
        let mut o = PatternOptions::default();
        o.bond = Bond::Staggered { weight: 0.5 };
        o.time_limit = Duration::from_secs_f64(seconds);
        o.method = method;
        o.formulation = formulation;
        o
    };
    let found = pattern::solve(&mesh, &options).expect("bench meshes are valid");
    println!(
        "{}",
        serde_json::to_string(&found).expect("a pattern serialises")
    );
    println!(
        "{}",
        peak_memory_mb().map_or("-".to_string(), |mb| format!("{mb:.0}"))
    );
    // A CBC worker still busy past the limit ends with the process.
    std::process::exit(0);
}

/// The process's resident-memory high-water mark in MB (Linux).
fn peak_memory_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}
