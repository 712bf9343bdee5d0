//! Creases (`mesh::crease`): the webs of a groin or a cloister vault each get quads and level
//! courses of their own, and the tiles are cut to the creases.

mod common;

use common::{json, s, scratch, tilepattern};

use nalgebra::Point3;
use tilepattern::mesh::{PolyMesh, generate, obj};
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

/// The height of two semicircular barrels crossing on a 3.6 m square: their lower envelope,
/// a groin vault standing on its corners, or their upper one, a cloister vault on walls all
/// round. Either way each web follows one barrel.
fn height(groin: bool) -> impl Fn(f64, f64) -> f64 {
    move |x: f64, y: f64| {
        let across = if (x.abs() >= y.abs()) == groin { y } else { x };
        (HALF * HALF - across * across).max(0.0).sqrt()
    }
}

/// [`height`] triangulated on a 48 x 48 grid whose cells split along the diagonals (as a
/// designer's mesh of the joined barrels has its edges on them).
fn crossed_barrels(groin: bool) -> PolyMesh {
    generate::diagonal_grid(48, HALF, height(groin))
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
    lays_every_web_level(true);
}

#[test]
fn a_cloister_vault_is_laid_in_level_courses_in_every_web_and_cut_to_its_valleys() {
    lays_every_web_level(false);
}

/// Each web of crossed barrels laid level, and cut to the creases between the webs.
fn lays_every_web_level(groin: bool) {
    let surface = &crossed_barrels(groin);
    let (remeshed, tiling) = common::run_level(surface, &SPEC, &FinishOptions::for_spec(&SPEC));
    assert_eq!(remeshed.metrics.crease_sheets, 4);
    // Level courses: a full tile's length runs along its web's barrel, level. (One field
    // over the whole vault turns at the groins, and half the webs' tiles climbed.)
    let full: Vec<_> = tiling
        .tiles
        .iter()
        .filter(|t| t.kind == TileKind::Full)
        .collect();
    assert!(full.len() > 150, "{}", full.len());
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
    // Whole tiles lie on their web: on the upper half of the vault (where the webs slope by
    // under 60 degrees) the corners of their bottom faces stay within 5 mm of the surface.
    // Quads running over a crease gave tiles bridging it, their ends centimetres off.
    let whole: Vec<_> = tiling
        .tiles
        .iter()
        .filter(|t| t.cut.is_none() && t.frame.origin.z > HALF / 2.0)
        .collect();
    let lying = whole
        .iter()
        .filter(|t| {
            let off: Vec<f64> = outline::world_outline(t)
                .iter()
                .map(|p| off_surface(p, groin))
                .collect();
            off.iter().copied().fold(f64::MIN, f64::max)
                - off.iter().copied().fold(f64::MAX, f64::min)
                < 0.005
        })
        .count();
    assert!(
        lying * 100 >= whole.len() * 95,
        "{lying} of {} lie on the surface",
        whole.len()
    );
}

/// Height of `p` over the crossed barrels, measured along the surface's normal.
fn off_surface(p: &Point3<f64>, groin: bool) -> f64 {
    let crossed = height(groin);
    let e = 1e-5;
    let dx = (crossed(p.x + e, p.y) - crossed(p.x - e, p.y)) / (2.0 * e);
    let dy = (crossed(p.x, p.y + e) - crossed(p.x, p.y - e)) / (2.0 * e);
    (p.z - crossed(p.x, p.y)) / (1.0 + dx * dx + dy * dy).sqrt()
}

/// The quads of `generate::grid(nx, ny)` with the grid's vertex `(i, j)` moved to `at(i, j)`.
fn grid_of(nx: usize, ny: usize, at: impl Fn(f64, f64) -> Point3<f64>) -> PolyMesh {
    let grid = generate::grid(nx, ny);
    let positions = grid.positions().iter().map(|p| at(p.x, p.y)).collect();
    PolyMesh::new(positions, grid.faces().to_vec()).unwrap()
}

/// A 2.4 x 1.2 m plate folded along x = 0 (the halves turn by 44 degrees), 24 x 12 quads.
fn folded_plate() -> PolyMesh {
    grid_of(24, 12, |i, j| {
        let x = 0.1 * (i - 12.0);
        Point3::new(x, 0.1 * j, 0.4 * x.abs())
    })
}

/// `tilepattern run` on `mesh` (written to `dir`) with 280 x 140 x 15 mm tiles, in metres,
/// into `dir/out` with `extra` flags: its report and what it printed.
fn run(
    mesh: &PolyMesh,
    dir: &std::path::Path,
    out: &str,
    extra: &[&str],
) -> (serde_json::Value, String) {
    let input = dir.join("input.obj");
    std::fs::write(&input, obj::to_string(mesh)).unwrap();
    let out_dir = dir.join(out);
    let mut args = vec!["run", s(&input), "--tile", "280x140x15", "--units", "m"];
    args.extend(["--out", s(&out_dir)]);
    args.extend(extra);
    let output = tilepattern(&args);
    let said = String::from_utf8_lossy(&output.stdout).into_owned()
        + &String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "{said}");
    (json(&out_dir.join("report.json")), said)
}

#[test]
fn the_command_line_splits_at_creases_unless_told_not_to() {
    let dir = scratch("creases");
    let run = |out: &str, extra: &[&str]| run(&folded_plate(), &dir, out, extra);
    let (split, said) = run("split", &[]);
    assert_eq!(split["remesh"]["crease_sheets"], 2);
    assert!(
        said.contains("split at its creases into 2 sheets"),
        "{said}"
    );
    // Cut to the fold, no tile stands off the plate by its thickness.
    let lifted = |report: &serde_json::Value| report["cutting"]["lifted_tiles"].as_u64().unwrap();
    let warned = |report: &serde_json::Value| {
        report["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w["code"] == "tiles_off_surface")
    };
    assert_eq!(lifted(&split), 0, "{}", split["cutting"]);
    assert!(!warned(&split));
    let (joined, said) = run("joined", &["--no-creases"]);
    assert_eq!(joined["remesh"]["crease_sheets"], 0);
    assert!(!said.contains("split at its creases"), "{said}");
}

/// A cloister vault on a 4.8 x 3 m rectangle, triangulated on a 48 x 30 grid: its valleys run
/// from the corners at 32 degrees to the long sides, across the triangles, where no mesh
/// edge lies for the crease split to follow.
fn rectangular_cloister() -> PolyMesh {
    let along = |s: f64, half: f64| (1.0 - (s / half).powi(2)).max(0.0).sqrt();
    generate::triangulate_quads(&grid_of(48, 30, |i, j| {
        let (x, y) = (-2.4 + 0.1 * i, -1.5 + 0.1 * j);
        Point3::new(x, y, 1.5 * along(x, 2.4).min(along(y, 1.5)))
    }))
}

#[test]
fn tiles_bridging_a_crease_across_the_triangles_are_reported() {
    // The crease split finds no crease along edges here, so the quads and the tiles run over
    // the valleys as if they were smooth: tiles bridge them, their ends off the surface.
    let (report, said) = run(
        &rectangular_cloister(),
        &scratch("creases-across"),
        "out",
        &[],
    );
    let cutting = &report["cutting"];
    assert!(cutting["lifted_tiles"].as_u64().unwrap() > 10, "{cutting}");
    assert!(
        cutting["largest_lift"].as_f64().unwrap() > 0.05,
        "{cutting}"
    );
    assert!(
        report["warnings"]
            .as_array()
            .unwrap()
            .iter()
            .any(|w| w["code"] == "tiles_off_surface"),
        "{}",
        report["warnings"]
    );
    assert!(said.contains("warning [tiles_off_surface]: "), "{said}");
}

#[test]
fn quads_given_without_a_surface_are_cut_at_their_own_creases() {
    // A plate folded along x = 0 in 16 x 8 quads of half a tile: no remesh, no surface; the
    // quads are the surface. Pairs across the fold become tiles cut to it, and every whole
    // tile lies on one of the two planes.
    let e = SPEC.quad_edge(false);
    let quads = grid_of(16, 8, |i, j| {
        let x = e * (i - 8.0);
        Point3::new(x, e * j, 0.4 * x.abs())
    });
    let tiling = tilepattern::pipeline::tile_quad_mesh(
        &quads,
        None,
        &tilepattern::pattern::PatternOptions::default(),
        &SPEC,
        &FinishOptions::for_spec(&SPEC),
        &mut tilepattern::control::Control::none(),
    )
    .unwrap();
    let plane_gap = |p: &Point3<f64>| (p.z - 0.4 * p.x.abs()).abs() / 0.4_f64.hypot(1.0);
    for tile in tiling.tiles.iter().filter(|t| t.cut.is_none()) {
        let outline = outline::world_outline(tile);
        let side = outline[0].x.signum();
        assert!(
            outline
                .iter()
                .all(|p| p.x.signum() == side && plane_gap(p) < 1e-3),
            "a whole tile over the fold: {outline:?}"
        );
    }
}

/// A folded-plate roof 8 x 4 m: seven folds across x, at every metre, rising 0.8 m over each;
/// 96 x 48 quads.
fn folded_roof() -> PolyMesh {
    grid_of(96, 48, |i, j| {
        let x = i / 12.0;
        Point3::new(x, j / 12.0, roof_plane(x, x))
    })
}

/// The height at `x` of the roof's plane that holds `on` (the one between the folds around
/// `on`, carried on beyond them).
fn roof_plane(on: f64, x: f64) -> f64 {
    let k = on.floor().clamp(0.0, 7.0);
    let rising = k % 2.0 == 0.0;
    let base = if rising { 0.0 } else { 0.8 };
    base + if rising { 0.8 } else { -0.8 } * (x - k)
}

#[test]
fn every_piece_of_a_folded_roof_lies_on_its_own_plane() {
    // Pieces filling the fit's tears took a course continued over a fold, and one at a valley's
    // end stood 225 mm off the roof.
    let (_, tiling) = common::run_level(&folded_roof(), &SPEC, &FinishOptions::for_spec(&SPEC));
    for tile in &tiling.tiles {
        let on = tile.frame.origin.x;
        for p in outline::world_outline(tile) {
            let off = (p.z - roof_plane(on, p.x)).abs() / 0.8_f64.hypot(1.0);
            assert!(
                off < 0.005,
                "{:?} {} at {p:?}: {off} off its plane",
                tile.kind,
                tile.label
            );
        }
    }
}
