//! Fit-stage benchmark (issue 16): the demo shell, every `/work/shared/surfaces/*.obj` (or
//! the directory given as the first argument) and a 50k-tile shell (the shared dome scaled
//! four times, 48 m), each tiled as `tilepattern run` tiles it (level courses, quads of the
//! course pitch, 280 x 140 x 15 mm tiles, 10 mm joint), with the pattern stage limited to
//! `TP_BENCH_PATTERN_LIMIT` seconds (default 20). For each: tiles, the joints before the fit
//! (the paper's section 3.5 placement) and after it, tiles cut to fit, the tiles of the
//! pattern kept on the surface with and without the fit, and the fit's seconds and peak
//! memory of the whole run. Prints a markdown table. The fit is then run once more alone for
//! its processor seconds (the wall-clock seconds count what else the machine runs).
//!
//! `cargo run --release --example fit_bench [surfaces-dir]`

use std::path::PathBuf;
use std::time::Duration;

use tilepattern::control::Control;
use tilepattern::mesh::{PolyMesh, generate, obj};
use tilepattern::pattern::{self, Courses, PatternOptions};
use tilepattern::pipeline;
use tilepattern::remesh::{self, RemeshOptions};
use tilepattern::report::JointSummary;
use tilepattern::tiles::{FinishOptions, TileSpec};

const SPEC: TileSpec = TileSpec {
    length: 0.28,
    width: 0.14,
    thickness: 0.015,
    joint: 0.01,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "/work/shared/surfaces".into()),
    );
    let limit: f64 = std::env::var("TP_BENCH_PATTERN_LIMIT")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(20.0);
    let mut cases: Vec<(String, PolyMesh)> = vec![(
        "demo (3 m)".into(),
        generate::triangulate_quads(&generate::corner_supported_shell(
            3.0,
            SPEC.target_edge() / 3.0,
        )),
    )];
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    files.sort();
    for file in &files {
        cases.push((
            file.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default(),
            obj::read(file)?,
        ));
    }
    if let Some(dome) = files
        .iter()
        .find(|f| f.file_stem().is_some_and(|s| s == "dome"))
    {
        let dome = obj::read(dome)?;
        let scaled = dome.positions().iter().map(|p| p * 4.0).collect();
        cases.push((
            "dome x4 (48 m)".into(),
            PolyMesh::new(scaled, dome.faces().to_vec())?,
        ));
    }
    println!(
        "| surface | tiles | p95 dev. before / after mm | within 2 mm before / after | overlapping pairs before / after | deepest overlap before / after mm | cut to fit | full + half kept, no fit / fit | fit status | fit s | fit CPU s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, surface) in cases {
        let courses = Courses::Level {
            up: [0.0, 0.0, 1.0],
        };
        let remeshed = remesh::remesh(&surface, &{
            let mut o = RemeshOptions::default();
            o.target_edge = SPEC.quad_edge(true);
            // The remesher's own limit is not what is measured here (the 50k case takes
            // over a minute on a loaded machine).
            o.time_limit = Duration::from_secs(1800);
            o
        })?;
        let options = {
            let mut o = PatternOptions::default();
            o.time_limit = Duration::from_secs_f64(limit);
            o.courses = courses;
            o
        };
        let found = pattern::solve(&remeshed.quads, &options)?;
        let finish = {
            let mut o = FinishOptions::for_spec(&SPEC);
            o.fit = FinishOptions::for_spec(&SPEC).fit.map(|f| {
                let mut o = f;
                o.time_limit = 60.0;
                o
            });
            o
        };
        let fitted = pipeline::tiles_for_pattern_with(
            &remeshed.quads,
            Some(&surface),
            found.clone(),
            &SPEC,
            &finish,
            &mut Control::none(),
        )?;
        let paper = pipeline::tiles_for_pattern(&remeshed.quads, Some(&surface), found, &SPEC, &{
            let mut o = finish;
            o.fit = None;
            o
        })?;
        // The fit alone again, for its processor seconds (the wall-clock seconds above count
        // whatever else the machine runs).
        let cpu_before = cpu_seconds();
        let boxes = tilepattern::tiles::build(&remeshed.quads, &fitted.pattern, &SPEC)?;
        let fit_options = finish.fit.expect("the fit is on");
        tilepattern::tiles::fit::fit(
            &remeshed.quads,
            Some(&surface),
            boxes,
            &SPEC,
            &fit_options,
            &mut Control::none(),
        )?;
        let fit_cpu = cpu_seconds()
            .zip(cpu_before)
            .map(|(after, before)| after - before);
        let j = &fitted.report.joints;
        let b: &JointSummary = j.before_fit.as_deref().expect("the fit ran");
        let fit = fitted.report.fit.expect("the fit ran");
        println!(
            "| {name} | {} | {:.1} / {:.1} | {:.0} % / {:.0} % | {} / {} | {:.1} / {:.1} | {} ({:.2} %) | {} / {} | {:?} ({} steps) | {:.2} | {} |",
            fitted.tiles.len(),
            b.p95_deviation * 1000.0,
            j.p95_deviation * 1000.0,
            100.0 * b.within_2mm,
            100.0 * j.within_2mm,
            b.overlaps,
            j.overlaps,
            b.max_overlap * 1000.0,
            j.max_overlap * 1000.0,
            j.fit_cuts,
            100.0 * j.fit_cuts as f64 / fitted.tiles.len().max(1) as f64,
            paper.report.full_tiles + paper.report.half_tiles,
            fitted.report.full_tiles + fitted.report.half_tiles,
            fit.status,
            fit.iterations,
            fitted.report.seconds.fit,
            fit_cpu.map_or("-".into(), |s| format!("{s:.2}"))
        );
    }
    Ok(())
}

/// Processor seconds this process has used (user and system), where `/proc` tells them.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (in parentheses): utime and stime are the 12th and 13th,
    // in clock ticks of (on Linux) a hundredth of a second.
    let rest = stat.get(stat.rfind(')')? + 2..)?;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}
