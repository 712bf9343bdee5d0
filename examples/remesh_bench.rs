//! Remesher benchmark: every `/work/shared/surfaces/*.obj` (or the directory given as the
//! first argument) at t = 0.14 m, printed as a markdown table of the acceptance metrics.
//! A second argument names a directory to write the quad meshes into.
//!
//! `cargo run --release --example remesh_bench [surfaces-dir] [out-dir]`

use std::path::PathBuf;

use tilepattern::mesh::obj;
use tilepattern::remesh::{RemeshOptions, remesh};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let dir = PathBuf::from(
        args.next()
            .unwrap_or_else(|| "/work/shared/surfaces".into()),
    );
    let out = args.next().map(PathBuf::from);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    files.sort();
    let options = {
        let mut o = RemeshOptions::default();
        o.target_edge = 0.14;
        o
    };
    println!(
        "| surface | faces | pure quad | irregular | bdry off | mean edge | edges ±20% | areas ±20% | p95 angle dev | max dist/t | covered | seconds |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for file in files {
        let name = file
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let input = obj::read(&file)?;
        match remesh(&input, &options) {
            Ok(result) => {
                let m = &result.metrics;
                println!(
                    "| {name} | {} | {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.1} | {:.3} | {:.4} | {:.2} |",
                    m.faces,
                    m.pure_quad,
                    m.interior_irregular_vertices,
                    m.boundary_vertices_off_input,
                    m.mean_edge_ratio,
                    m.edges_within_20pct,
                    m.faces_area_within_20pct,
                    m.p95_corner_angle_deviation_deg,
                    m.max_distance_to_input_ratio,
                    m.area_covered_ratio,
                    m.seconds
                );
                if let Some(out) = &out {
                    std::fs::create_dir_all(out)?;
                    obj::write(&result.quads, &out.join(format!("{name}.obj")))?;
                }
            }
            Err(e) => println!("| {name} | error: {e} |"),
        }
    }
    Ok(())
}
