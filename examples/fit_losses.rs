//! Where the fit stage (issue 16) loses tiles and where its worst joints are: each surface
//! tiled as `fit_bench` tiles it (level courses, quads of [`TileSpec::quad_edge`] times
//! `TP_QUAD_SCALE`, default 1; 280 x 140 x 15 mm tiles, 10 mm joint; the pattern stage
//! limited to `TP_BENCH_PATTERN_LIMIT` seconds, default 5), then:
//! - the tiles of the pattern the fit loses (`finish` drops them after the fit, not without
//!   it): how many, how many of them the boundary already cut without the fit (a tile of
//!   the outer course overhanging the edge, pushed further out), and how far the fit moved
//!   them along and across their course (medians);
//! - the quads' extent across their tile (mean and 10th percentile; a course needs W + joint);
//! - the joints after the fit: p95 `|gap - joint|`, and of those beyond it, the share within
//!   three quad edges of an irregular interior vertex of the quad mesh (against the share of
//!   all joints there), the share that are too wide (rather than too narrow), and the share
//!   touching a tile the fit or the boundary cut.
//!
//! `cargo run --release --example fit_losses [demo|SURFACE.obj ...]` (default: the demo and
//! `/work/shared/surfaces/*.obj`).

use std::collections::HashSet;
use std::path::Path;
use std::time::Duration;

use nalgebra::Vector3;
use tilepattern::control::Control;
use tilepattern::mesh::{Topology, generate, obj};
use tilepattern::pattern::{self, Courses, PatternOptions};
use tilepattern::remesh::{self, RemeshOptions};
use tilepattern::report::gaps;
use tilepattern::tiles::{self, FinishOptions, TileKind, TileSpec};

const SPEC: TileSpec = TileSpec {
    length: 0.28,
    width: 0.14,
    thickness: 0.015,
    joint: 0.01,
};

fn env(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// The `q`-quantile of `v` (sorted in place); NaN when empty.
fn quantile(v: &mut [f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut inputs: Vec<String> = std::env::args().skip(1).collect();
    if inputs.is_empty() {
        inputs.push("demo".into());
        let mut files: Vec<String> = std::fs::read_dir("/work/shared/surfaces")?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "obj"))
            .map(|p| p.to_string_lossy().into_owned())
            .collect();
        files.sort();
        inputs.extend(files);
    }
    let limit = env("TP_BENCH_PATTERN_LIMIT", 5.0);
    let scale = env("TP_QUAD_SCALE", 1.0);
    println!(
        "| surface | quads | irregular | tiles | lost by the fit (off / sliver) | lost: cut to the boundary without the fit | lost: median move along / across mm | quad extent across: mean / p10 mm | p95 dev. mm | fit cuts | beyond p95: near irregular (all joints) | beyond p95: too wide | beyond p95: by a cut tile |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for input in inputs {
        let (name, surface) = if input == "demo" {
            (
                "demo".to_string(),
                generate::triangulate_quads(&generate::corner_supported_shell(
                    3.0,
                    SPEC.target_edge() / 3.0,
                )),
            )
        } else {
            let path = Path::new(&input);
            let name = path
                .file_stem()
                .map_or(input.clone(), |s| s.to_string_lossy().into_owned());
            (name, obj::read(path)?)
        };
        let edge = SPEC.quad_edge(true) * scale;
        let quads = remesh::remesh(&surface, &{
            let mut o = RemeshOptions::default();
            o.target_edge = edge;
            o.time_limit = Duration::from_secs(1800);
            o
        })?
        .quads;
        let found = pattern::solve(&quads, &{
            let mut o = PatternOptions::default();
            o.time_limit = Duration::from_secs_f64(limit);
            o.courses = Courses::Level {
                up: [0.0, 0.0, 1.0],
            };
            o
        })?;
        let finish = FinishOptions::for_spec(&SPEC);
        let fit_options = finish.fit.expect("the fit is on by default");
        let boxes = tiles::build(&quads, &found, &SPEC)?;
        let (fitted, _) = tiles::fit::fit(
            &quads,
            Some(&surface),
            boxes.clone(),
            &SPEC,
            &fit_options,
            &mut Control::none(),
        )?;
        let no_fit = {
            let mut o = finish;
            o.fit = None;
            o
        };
        let (_, paper) = tiles::finish(&quads, Some(&surface), boxes.clone(), &SPEC, &no_fit);
        let (placed, finished) =
            tiles::finish(&quads, Some(&surface), fitted.clone(), &SPEC, &finish);

        // The tiles of the pattern the fit loses, and how far it moved them.
        let key = |faces: &[usize]| {
            let mut f = faces.to_vec();
            f.sort_unstable();
            f
        };
        let lost_anyway: HashSet<Vec<usize>> =
            paper.dropped.iter().map(|d| key(&d.faces)).collect();
        let lost: Vec<_> = finished
            .dropped
            .iter()
            .filter(|d| !lost_anyway.contains(&key(&d.faces)))
            .collect();
        let slivers = lost
            .iter()
            .filter(|d| d.reason == tiles::DropReason::Sliver)
            .count();
        let tile_of: std::collections::HashMap<Vec<usize>, usize> = boxes
            .iter()
            .enumerate()
            .map(|(i, t)| (key(&t.faces), i))
            .collect();
        let (mut along, mut across): (Vec<f64>, Vec<f64>) = lost
            .iter()
            .filter_map(|d| tile_of.get(&key(&d.faces)))
            .map(|&i| {
                let (a, f) = (&boxes[i].frame, &fitted[i].frame);
                let m = f.origin - a.origin;
                (m.dot(&a.x).abs() * 1000.0, m.dot(&a.y).abs() * 1000.0)
            })
            .unzip();

        // Of those, the ones the boundary cut already where the section 3.5 placement put
        // them: outer-course tiles overhanging the edge that the fit pushed further out.
        let boundary = tiles::SurfaceBoundary::new(&surface, SPEC.length.max(SPEC.width));
        let overhanging = lost
            .iter()
            .filter_map(|d| tile_of.get(&key(&d.faces)))
            .filter(|&&i| {
                matches!(
                    boundary.clip(&boxes[i], finish.tolerance),
                    tiles::clip::Clipped::Cut(_)
                )
            })
            .count();

        // Each quad's extent across the tile on it.
        let mut extents: Vec<f64> = boxes
            .iter()
            .flat_map(|t| {
                t.faces.iter().map(|&f| {
                    let ys = quads
                        .face_points(f)
                        .map(|p| (p - t.frame.origin).dot(&t.frame.y));
                    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
                        (lo.min(y), hi.max(y))
                    });
                    (hi - lo) * 1000.0
                })
            })
            .collect();
        let mean_extent = extents.iter().sum::<f64>() / extents.len().max(1) as f64;

        // Irregular interior vertices of the quad mesh.
        let topology = Topology::new(&quads)?;
        let irregular: Vec<Vector3<f64>> = (0..quads.positions().len())
            .filter(|&v| {
                let valence = topology.vertex_edges(v).len();
                !topology.is_boundary_vertex(v) && valence != 4 && valence != 0
            })
            .map(|v| quads.positions()[v].coords)
            .collect();
        let near_irregular =
            |p: &Vector3<f64>| irregular.iter().any(|q| (q - p).norm() < 3.0 * edge);

        let joints = gaps::joints(&quads, &placed, SPEC.joint);
        let mut devs: Vec<f64> = joints.iter().map(|j| (j.gap - SPEC.joint).abs()).collect();
        let p95 = quantile(&mut devs, 0.95);
        let (mut all_near, mut beyond, mut beyond_near, mut wide, mut by_cut) = (0, 0, 0, 0, 0);
        for j in &joints {
            let [a, b] = j.tiles;
            let mid = (placed[a].frame.origin.coords + placed[b].frame.origin.coords) / 2.0;
            let near = near_irregular(&mid);
            all_near += usize::from(near);
            if (j.gap - SPEC.joint).abs() <= p95 {
                continue;
            }
            beyond += 1;
            beyond_near += usize::from(near);
            wide += usize::from(j.gap > SPEC.joint);
            by_cut += usize::from(placed[a].cut.is_some() || placed[b].cut.is_some());
        }
        let share = |n: usize, of: usize| 100.0 * n as f64 / of.max(1) as f64;
        let fit_cuts = placed.iter().filter(|t| t.kind == TileKind::FitCut).count();
        println!(
            "| {name} | {} | {} | {} | {} ({} / {slivers}) | {overhanging} | {:.0} / {:.0} | {mean_extent:.1} / {:.1} | {:.1} | {fit_cuts} | {:.0} % ({:.0} %) | {:.0} % | {:.0} % |",
            quads.face_count(),
            irregular.len(),
            boxes.len(),
            lost.len(),
            lost.len() - slivers,
            quantile(&mut along, 0.5),
            quantile(&mut across, 0.5),
            quantile(&mut extents, 0.1),
            p95 * 1000.0,
            share(beyond_near, beyond),
            share(all_near, joints.len()),
            share(wide, beyond),
            share(by_cut, beyond),
        );
    }
    Ok(())
}
