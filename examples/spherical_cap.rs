//! Writes a spherical cap as an OBJ triangle mesh (the remesher's umbilic test dome, see
//! [`tilepattern::mesh::generate::spherical_cap`]).
//!
//! `cargo run --release --example spherical_cap -- RADIUS OUT.obj [AREA_FRACTION] [EDGE]`
//!
//! Defaults: 0.6 of the sphere (the rim overhangs), triangle edges of 0.087 model units.
//! `-- 10 cap10.obj` gives the benchmark's 20 m dome (about 200k triangles), `-- 3 cap3.obj`
//! the 3 m one of `tests/remesh.rs`.

use tilepattern::mesh::{generate, obj};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: spherical_cap RADIUS OUT.obj [AREA_FRACTION] [EDGE]";
    let (Some(radius), Some(out)) = (args.first(), args.get(1)) else {
        return Err(usage.into());
    };
    let radius: f64 = radius.parse()?;
    let fraction: f64 = args.get(2).map_or(Ok(0.6), |s| s.parse())?;
    let edge: f64 = args.get(3).map_or(Ok(0.087), |s| s.parse())?;
    if !(radius.is_finite() && radius > edge && edge > 0.0 && fraction > 0.0 && fraction < 1.0) {
        return Err(usage.into());
    }
    let cap = generate::spherical_cap(radius, fraction, edge);
    obj::write(&cap, std::path::Path::new(out))?;
    println!(
        "{out}: radius {radius}, {fraction} of the sphere, {} vertices, {} triangles",
        cap.positions().len(),
        cap.face_count()
    );
    Ok(())
}
