//! Creases (`mesh::crease`): a groin vault's webs each get quads and level courses of their
//! own, and the tiles are cut to the groins.

use std::time::Duration;

use nalgebra::Point3;
use tilepattern::control::Control;
use tilepattern::mesh::PolyMesh;
use tilepattern::pattern::{Courses, PatternOptions};
use tilepattern::pipeline;
use tilepattern::remesh::RemeshOptions;
use tilepattern::tiles::{FinishOptions, TileKind, TileSpec, outline};

/// 280 x 140 x 15 mm tiles with a 10 mm joint, in metres.
const SPEC: TileSpec = TileSpec {
    length: 0.28,
    width: 0.14,
    thickness: 0.015,
    joint: 0.01,
};

/// Half the span of the groin vault.
const HALF: f64 = 1.8;

/// A groin vault on a 3.6 m square: two semicircular barrels crossing, triangulated on a
/// 48 x 48 grid whose cells split along the groins (as a designer's mesh of the joined
/// barrels has its edges on them).
fn groin_vault() -> PolyMesh {
    let n = 48;
    let at = |i: usize| -HALF + 2.0 * HALF * i as f64 / n as f64;
    let mut positions = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (at(i), at(j));
            let across = if x.abs() >= y.abs() { x } else { y };
            positions.push(Point3::new(
                x,
                y,
                (HALF * HALF - across * across).max(0.0).sqrt(),
            ));
        }
    }
    let id = |i: usize, j: usize| i * (n + 1) + j;
    let mut faces = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                faces.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                faces.extend([vec![a, b, d], vec![b, c, d]]);
            }
        }
    }
    PolyMesh::new(positions, faces).unwrap()
}

/// The web a plan point lies in: 0 and 1 the barrel along y (x > 0, x < 0), 2 and 3 the
/// barrel along x.
fn web(p: &Point3<f64>) -> usize {
    match (p.x.abs() >= p.y.abs(), p.x > 0.0, p.y > 0.0) {
        (true, true, _) => 0,
        (true, false, _) => 1,
        (false, _, true) => 2,
        (false, _, false) => 3,
    }
}

#[test]
fn a_groin_vault_is_laid_in_level_courses_in_every_web_and_cut_to_its_groins() {
    let surface = groin_vault();
    let options = {
        let mut o = PatternOptions::default();
        o.time_limit = Duration::from_secs(5);
        o.courses = Courses::Level {
            up: [0.0, 0.0, 1.0],
        };
        o
    };
    let remesh = {
        let mut o = RemeshOptions::default();
        o.target_edge = SPEC.quad_edge(true);
        o
    };
    let (remeshed, tiling) = pipeline::tile_surface(
        &surface,
        &remesh,
        &options,
        &SPEC,
        &FinishOptions::for_spec(&SPEC),
        &mut Control::none(),
    )
    .unwrap();
    assert_eq!(remeshed.metrics.crease_sheets, 4);
    // Level courses: a full tile's length runs along its web's barrel, level. (One field
    // over the whole vault turns at the groins, and half the webs' tiles climbed.)
    let full: Vec<_> = tiling
        .tiles
        .iter()
        .filter(|t| t.kind == TileKind::Full)
        .collect();
    assert!(full.len() > 300, "{}", full.len());
    let level = full.iter().filter(|t| t.frame.x.z.abs() < 0.05).count();
    assert!(
        level * 100 >= full.len() * 95,
        "{level} of {} level",
        full.len()
    );
    // No tile crosses a groin: what is kept of each lies in the web of its centre. Its plane
    // is tangent there, so a point of its outline may stand a little over the groin in plan
    // where the surface curves away under it: 3 mm on the upper half of the vault, where
    // the webs slope by less than 60 degrees (towards the springings, ever more in plan).
    for (i, tile) in tiling.tiles.iter().enumerate() {
        let own = web(&tile.frame.origin);
        for p in outline::world_outline(tile)
            .into_iter()
            .filter(|p| p.z > HALF / 2.0)
        {
            let over_groin = (p.x.abs() - p.y.abs()).abs() / std::f64::consts::SQRT_2;
            assert!(
                web(&p) == own || over_groin < 0.003,
                "tile {i} ({:?}, {}) crosses a groin at {p:?}",
                tile.kind,
                tile.label
            );
        }
    }
    // The webs' own courses fit: hardly anything cut to fit, joints even.
    let fit_cuts = tiling.tiles.iter().filter(|t| t.fit_cut).count();
    assert!(fit_cuts * 100 <= full.len(), "{fit_cuts} cut to fit");
    let joints = &tiling.report.joints;
    assert!(joints.p95_deviation < 0.002, "{}", joints.p95_deviation);
}
