//! Matching benchmark: the staggered model (eq. 2, w = 0.5) on n x n grids and on the
//! QuadriFlow meshes in `../shared/surfaces/quads/`, solved by the default engine and by the
//! paper's whole program on CBC with the same time limit. Writes a markdown table to stdout
//! and to `target/bench/matching.md`.
//!
//! `cargo bench --bench matching` (all rows), or with arguments to pick rows, e.g.
//! `cargo bench --bench matching -- grid10 grid24 hypar`. `TP_BENCH_LIMIT` sets the time
//! limit in seconds (default 60).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

use tilepattern::mesh::{PolyMesh, generate, obj};
use tilepattern::pattern::{self, Bond, Formulation, Method, PatternOptions};

fn main() {
    let limit: f64 = std::env::var("TP_BENCH_LIMIT").ok().and_then(|s| s.parse().ok()).unwrap_or(60.0);
    let wanted: Vec<String> = std::env::args().skip(1).filter(|a| !a.starts_with('-')).collect();
    let mut cases: Vec<(String, PolyMesh)> = [10, 14, 17, 24, 41, 100].iter().map(|&n| (format!("grid{n}"), generate::grid(n, n))).collect();
    let shared = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/surfaces/quads");
    for name in ["hypar", "tubemesh", "vault", "dome"] {
        if let Ok(mesh) = obj::read(&shared.join(format!("{name}.obj"))) {
            cases.push((format!("quadriflow-{name}"), mesh));
        }
    }
    let mut table = format!("| mesh | faces | method | seconds | status | objective | bound | gap % |\n|---|---|---|---|---|---|---|---|\n");
    println!("time limit {limit} s per solve, staggered w = 0.5\n");
    print!("{table}");
    for (name, mesh) in cases {
        if !wanted.is_empty() && !wanted.iter().any(|w| name.contains(w.as_str())) {
            continue;
        }
        for (label, method, formulation) in [("auto", Method::Auto, Formulation::Strengthened), ("paper MIP (CBC)", Method::Mip, Formulation::Paper)] {
            let options = PatternOptions {
                bond: Bond::Staggered { weight: 0.5 },
                time_limit: Duration::from_secs_f64(limit),
                method,
                formulation,
                ..PatternOptions::default()
            };
            let found = pattern::solve(&mesh, &options).expect("bench meshes are valid");
            let row = format!(
                "| {name} | {} | {label} | {:.2} | {:?} | {} | {:.1} | {:.2} |\n",
                mesh.face_count(),
                found.seconds,
                found.status,
                found.objective,
                found.bound,
                100.0 * found.gap
            );
            print!("{row}");
            table.push_str(&row);
        }
    }
    let out = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/bench");
    std::fs::create_dir_all(&out).expect("target is writable");
    let mut text = format!("Staggered matching (eq. 2, w = 0.5), time limit {limit} s per solve.\n\n");
    let _ = write!(text, "{table}");
    std::fs::write(out.join("matching.md"), text).expect("target is writable");
}
