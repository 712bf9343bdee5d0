//! The fit stage (issue 16): tiles moved on the surface so that every joint comes close to
//! the mortar joint, what cannot fit cut, no two tiles overlapping, checked independently of
//! the stage's own joint measure.

mod common;

use std::time::Duration;

use nalgebra::Point3;
use tilepattern::control::Control;
use tilepattern::mesh::{PolyMesh, generate};
use tilepattern::pattern::{Bond, Courses, PatternOptions};
use tilepattern::pipeline::{self, Tiling};
use tilepattern::remesh::RemeshOptions;
use tilepattern::tiles::{FinishOptions, FitStatus, TileError, TileKind, TileSpec};

/// 280 x 140 x 15 mm tiles with a 10 mm joint, in metres.
const SPEC: TileSpec = TileSpec {
    length: 0.28,
    width: 0.14,
    thickness: 0.015,
    joint: 0.01,
};

/// A triangle mesh over `nu` x `nv` cells of the parameter square, lifted by `at`.
fn sheet(nu: usize, nv: usize, at: impl Fn(f64, f64) -> [f64; 3]) -> PolyMesh {
    let mut positions = Vec::new();
    for j in 0..=nv {
        for i in 0..=nu {
            let p = at(i as f64 / nu as f64, j as f64 / nv as f64);
            positions.push(Point3::new(p[0], p[1], p[2]));
        }
    }
    let mut faces = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let a = j * (nu + 1) + i;
            faces.push(vec![a, a + 1, a + nu + 2]);
            faces.push(vec![a, a + nu + 2, a + nu + 1]);
        }
    }
    PolyMesh::new(positions, faces).unwrap()
}

/// Half a barrel vault: radius 1.5 m, 2 m long (developable: tiles can fit it exactly).
fn barrel() -> PolyMesh {
    sheet(60, 40, |u, v| {
        let a = std::f64::consts::PI * (1.0 - u);
        [1.5 * a.cos(), 2.0 * v, 1.5 * a.sin()]
    })
}

/// 95th percentile of `|gap - joint|` over the joints between tiles of the pattern (filler
/// pieces, which are cut to whatever room the courses leave, aside).
fn pattern_p95(tiling: &Tiling) -> f64 {
    let on_quads = |t: usize| !tiling.tiles[t].faces.is_empty();
    let mut d: Vec<f64> = tiling
        .joints
        .iter()
        .filter(|j| on_quads(j.tiles[0]) && on_quads(j.tiles[1]))
        .map(|j| (j.gap - SPEC.joint).abs())
        .collect();
    d.sort_by(f64::total_cmp);
    d[(d.len() * 95).div_ceil(100) - 1]
}

/// The whole pipeline in level courses, as `tilepattern run` lays tiles.
fn tile(surface: &PolyMesh, finish: &FinishOptions) -> Tiling {
    common::run_level(surface, &SPEC, finish).1
}

#[test]
fn on_a_developable_barrel_every_joint_fits() {
    let tiling = tile(&barrel(), &FinishOptions::for_spec(&SPEC));
    let joints = &tiling.report.joints;
    let before = joints.before_fit.as_ref().expect("the fit ran");
    assert!(
        pattern_p95(&tiling) <= 0.0005,
        "p95 |gap - joint| {} m between tiles (before the fit {})",
        pattern_p95(&tiling),
        before.p95_deviation
    );
    assert!(
        joints.p95_deviation < before.p95_deviation,
        "all joints, filler pieces included: {joints:?}"
    );
    assert!(
        before.p95_deviation > 0.002,
        "the section 3.5 placement does not fit: {}",
        before.p95_deviation
    );
    assert!(
        joints.max_overlap <= 0.001 && joints.fit_cuts == 0,
        "{joints:?}"
    );
    assert!(common::overlapping_tiles(&tiling.tiles, 0.001, 0.004).is_empty());
    assert_eq!(tiling.report.fit.unwrap().status, FitStatus::Converged);
    // Every tile stays on the surface: origin on it, thickness axis along its normal.
    let surface = barrel();
    for t in &tiling.tiles {
        let o = t.frame.origin;
        let radial = nalgebra::Vector3::new(o.x, 0.0, o.z);
        assert!(
            (radial.norm() - 1.5).abs() < 0.001 || t.faces.is_empty(),
            "origin {o} off the barrel"
        );
        if !t.faces.is_empty() {
            assert!(
                t.frame.z.dot(&radial.normalize()) > 1.0_f64.to_radians().cos() - 1e-3,
                "tile normal off the surface's at {o}"
            );
        }
    }
    assert!(surface.face_count() > 0);
}

/// Half a conical frustum: radius 3 m at the springing, 1.5 m at the top, 2 m high.
/// Developable, so tiles can fit it exactly, in courses straight on its development.
fn conical_vault() -> PolyMesh {
    sheet(120, 60, |u, v| {
        let (a, r) = (std::f64::consts::PI * u, 3.0 - 1.5 * v);
        [r * a.cos(), r * a.sin(), 2.0 * v]
    })
}

#[test]
fn on_a_developable_conical_vault_every_joint_fits() {
    // Its four corners make `run`'s first five tries follow its edges, and rows along the
    // curved arcs at the springing and the top converge as those arcs do; the sixth try
    // lays the smooth field free of the boundary, parallel on the development, its rows cut
    // to the arcs (issue 16: a developable surface, cylinder or cone, where perfect joints
    // exist: p95 at most 0.5 mm and no overlap).
    let mut options = PatternOptions::default();
    options.courses = Courses::Level {
        up: [0.0, 0.0, 1.0],
    };
    options.time_limit = Duration::from_secs(10);
    let mut remesh = RemeshOptions::default();
    remesh.target_edge = SPEC.quad_edge(true);
    let (quads, tiling) = pipeline::tile_surface_tries(
        &conical_vault(),
        &remesh,
        &options,
        &SPEC,
        &FinishOptions::for_spec(&SPEC),
        pipeline::Tries::Auto,
        &mut Control::none(),
    )
    .unwrap();
    let r = &tiling.report;
    let free: Vec<bool> = r.tries.iter().map(|x| x.boundary_free).collect();
    assert_eq!(
        free,
        [false, false, false, false, false, true],
        "{:?}",
        r.tries
    );
    assert_eq!(r.chosen_try, Some(5), "{:?}", r.tries);
    assert!(
        r.tries[..5].iter().all(|x| x.p95_deviation > 0.001),
        "{:?}",
        r.tries
    );
    assert!(!quads.metrics.aligned_boundary);
    assert_eq!(quads.metrics.interior_irregular_vertices, 0);
    assert!(
        pattern_p95(&tiling) <= 0.0005,
        "p95 |gap - joint| {} m between tiles",
        pattern_p95(&tiling)
    );
    let joints = &r.joints;
    assert!(joints.p95_deviation <= 0.0005, "{joints:?}");
    assert!(
        joints.max_overlap <= 0.001 && joints.fit_cuts == 0,
        "{joints:?}"
    );
    assert!(common::overlapping_tiles(&tiling.tiles, 0.001, 0.004).is_empty());
}

#[test]
fn tiles_laid_without_a_joint_are_not_cut_for_overlaps_below_a_tiles_own_tolerance() {
    // Dry-laid tiles (no joint) on the paper's 4 m corner-supported shell: the fit leaves
    // the tiles touching, some a few tenths of a millimetre into each other, which a tile's
    // own size varies by; cut to a tolerance of a thousandth of the width, 78 of its 465
    // tiles lost a 0.2 mm strip.
    let spec = TileSpec { joint: 0.0, ..SPEC };
    let surface = generate::triangulate_quads(&generate::corner_supported_shell(4.0, 0.0667));
    let tiling = common::run_level(&surface, &spec, &FinishOptions::for_spec(&spec)).1;
    let joints = &tiling.report.joints;
    assert_eq!(joints.fit_cuts, 0, "{joints:?}");
    assert!(joints.max_overlap <= 0.0005, "{joints:?}");
}

#[test]
fn no_two_tiles_overlap_on_doubly_curved_shells() {
    // The paper's corner-supported shell and a hypar, both doubly curved: the fit cannot make
    // every joint exact, and cuts what it cannot fit.
    let shell = generate::triangulate_quads(&generate::corner_supported_shell(2.5, 0.05));
    let hypar = sheet(40, 40, |u, v| {
        let (x, y) = (3.0 * u - 1.5, 3.0 * v - 1.5);
        [x, y, 0.25 * x * y]
    });
    for (name, surface) in [("shell", shell), ("hypar", hypar)] {
        let tiling = tile(&surface, &FinishOptions::for_spec(&SPEC));
        let joints = &tiling.report.joints;
        let before = joints.before_fit.as_ref().unwrap();
        assert!(
            joints.p95_deviation < before.p95_deviation,
            "{name}: {joints:?}"
        );
        assert!(
            pattern_p95(&tiling) <= 0.003,
            "{name}: p95 {} between tiles",
            pattern_p95(&tiling)
        );
        assert!(
            joints.max_overlap <= 0.001,
            "{name}: deepest overlap {}",
            joints.max_overlap
        );
        let overlaps = common::overlapping_tiles(&tiling.tiles, 0.001, 0.004);
        assert!(
            overlaps.is_empty(),
            "{name}: overlapping tiles {overlaps:?}"
        );
        // Filler pieces are cut to the room the fitted tiles leave: none of their joints is
        // narrower than the joint, and most are the joint.
        let filler = |t: usize| tiling.tiles[t].faces.is_empty();
        let filler_gaps: Vec<f64> = tiling
            .joints
            .iter()
            .filter(|j| filler(j.tiles[0]) || filler(j.tiles[1]))
            .map(|j| j.gap)
            .collect();
        let exact = filler_gaps
            .iter()
            .filter(|&&g| (g - SPEC.joint).abs() <= 0.002)
            .count();
        assert!(
            exact * 10 >= filler_gaps.len() * 8 && !filler_gaps.is_empty(),
            "{name}: {exact} of {} filler joints within 2 mm",
            filler_gaps.len()
        );
        assert!(
            filler_gaps.iter().all(|&g| g >= SPEC.joint - 1e-6),
            "{name}: filler joints {filler_gaps:?}"
        );
        // Cutting to fit stays rare, and cut tiles are listed like boundary cuts.
        let cut = tiling
            .tiles
            .iter()
            .filter(|t| t.kind == TileKind::FitCut)
            .count();
        assert!(
            cut * 50 <= tiling.tiles.len(),
            "{name}: {cut} of {} tiles cut to fit",
            tiling.tiles.len()
        );
        assert_eq!(
            cut,
            tiling
                .tiles
                .iter()
                .filter(|t| t.fit_cut && t.kind == TileKind::FitCut)
                .count()
        );
        assert!(
            tiling
                .cut_list
                .iter()
                .filter(|g| g.kind == TileKind::FitCut)
                .all(|g| g.label.starts_with('C') && !g.outline.is_empty())
        );
    }
}

#[test]
fn without_the_fit_tiles_keep_the_papers_placement() {
    let surface = generate::triangulate_quads(&generate::corner_supported_shell(1.5, 0.05));
    let fitted = tile(&surface, &FinishOptions::for_spec(&SPEC));
    let paper = tile(&surface, &{
        let mut o = FinishOptions::for_spec(&SPEC);
        o.fit = None;
        o
    });
    assert!(paper.report.fit.is_none() && paper.report.joints.before_fit.is_none());
    assert!(
        paper
            .tiles
            .iter()
            .all(|t| !t.fit_cut && t.kind != TileKind::FitCut)
    );
    // The same blanks either way: the fit moves tiles, it does not change the pattern.
    assert_eq!(
        (fitted.report.full_tiles, fitted.report.half_tiles),
        (paper.report.full_tiles, paper.report.half_tiles),
        "dropped {:?} vs {:?}",
        fitted.dropped,
        paper.dropped
    );
    let before = fitted.report.joints.before_fit.as_ref().unwrap();
    assert_eq!(before.contacts, paper.report.joints.contacts);
}

#[test]
fn a_cancelled_or_timed_out_fit_keeps_the_placement_so_far() {
    let quads = generate::corner_supported_shell(1.5, SPEC.quad_edge(true));
    let options = {
        let mut o = PatternOptions::default();
        o.time_limit = Duration::from_secs(2);
        o.courses = Courses::Level {
            up: [0.0, 0.0, 1.0],
        };
        o
    };
    let pattern = tilepattern::pattern::solve(&quads, &options).unwrap();
    let mut finish = FinishOptions::for_spec(&SPEC);
    let mut calls = 0;
    let mut stop = |_: f64| {
        calls += 1;
        false
    };
    let tiling = pipeline::tiles_for_pattern_with(
        &quads,
        None,
        pattern.clone(),
        &SPEC,
        &finish,
        &mut Control::with_progress(&mut stop),
    )
    .unwrap();
    assert_eq!(tiling.report.fit.unwrap().status, FitStatus::Cancelled);
    assert!(calls >= 1);
    finish.fit.as_mut().unwrap().time_limit = 0.0;
    let tiling = pipeline::tiles_for_pattern(&quads, None, pattern, &SPEC, &finish).unwrap();
    assert_eq!(tiling.report.fit.unwrap().status, FitStatus::TimeLimit);
    assert!(
        tiling
            .tiles
            .iter()
            .all(|t| t.corners.iter().flatten().all(|c| c.is_finite()))
    );
}

/// Two quads of 30 m carrying one tile of 1.9 m: the fit's tear fill is asked to cover the
/// rest of the 60 x 30 m with pieces (as a tile in the wrong units would ask).
fn one_tile_on_large_quads() -> (PolyMesh, tilepattern::pattern::Pattern, TileSpec) {
    let grid = generate::grid(2, 1);
    let quads = PolyMesh::new(
        grid.positions().iter().map(|p| p * 30.0).collect(),
        grid.faces().to_vec(),
    )
    .unwrap();
    let spec = TileSpec {
        length: 1.9,
        width: 0.95,
        thickness: 0.1,
        joint: 0.1,
    };
    let options = {
        let mut o = PatternOptions::default();
        o.bond = Bond::Stack;
        o
    };
    let pattern = tilepattern::pattern::solve(&quads, &options).unwrap();
    (quads, pattern, spec)
}

#[test]
fn the_fill_of_the_tears_stops_on_cancel_and_at_the_time_limit() {
    let (quads, pattern, spec) = one_tile_on_large_quads();
    let mut finish = FinishOptions::for_spec(&spec);
    let whole = pipeline::tiles_for_pattern(&quads, None, pattern.clone(), &spec, &finish).unwrap();
    let pieces = whole.report.cutting.as_ref().unwrap().tear_pieces;
    assert!(pieces >= 20, "{pieces} pieces fill the quads");
    assert_ne!(whole.report.fit.unwrap().status, FitStatus::Cancelled);
    // Cancelled once the fit has reported its end (1), i.e. in the fill.
    let mut ends = 0;
    let mut stop = |fraction: f64| {
        if fraction >= 1.0 {
            ends += 1;
        }
        ends < 2
    };
    let cancelled = pipeline::tiles_for_pattern_with(
        &quads,
        None,
        pattern.clone(),
        &spec,
        &finish,
        &mut Control::with_progress(&mut stop),
    )
    .unwrap();
    assert_eq!(cancelled.report.fit.unwrap().status, FitStatus::Cancelled);
    assert!(
        cancelled.report.cutting.as_ref().unwrap().tear_pieces < pieces,
        "{} of {pieces} pieces laid after the cancel",
        cancelled.report.cutting.as_ref().unwrap().tear_pieces
    );
    assert_eq!(ends, 2, "no progress reported after the cancel");
    // No time at all: the fill stops at its first look at the clock.
    finish.fit.as_mut().unwrap().time_limit = 0.0;
    let hurried = pipeline::tiles_for_pattern(&quads, None, pattern, &spec, &finish).unwrap();
    assert_eq!(hurried.report.fit.unwrap().status, FitStatus::TimeLimit);
    let laid = hurried.report.cutting.as_ref().unwrap().tear_pieces;
    assert!(laid < pieces, "{laid} of {pieces} pieces laid with no time");
}

#[test]
fn bad_fit_options_and_foreign_patterns_are_refused() {
    let quads = generate::grid(4, 2);
    let spec = TileSpec {
        length: 1.9,
        width: 0.95,
        thickness: 0.1,
        joint: 0.1,
    };
    let pattern = tilepattern::pattern::solve(&quads, &{
        let mut o = PatternOptions::default();
        o.bond = Bond::Stack;
        o
    })
    .unwrap();
    let with = |change: &dyn Fn(&mut tilepattern::tiles::FitOptions)| {
        let mut finish = FinishOptions::for_spec(&spec);
        change(finish.fit.as_mut().unwrap());
        pipeline::tiles_for_pattern(&quads, None, pattern.clone(), &spec, &finish)
            .unwrap_err()
            .to_string()
    };
    assert!(with(&|f| f.overlap_tolerance = f64::NAN).contains("overlap_tolerance"));
    assert!(with(&|f| f.time_limit = -1.0).contains("time_limit"));
    assert!(with(&|f| f.bond_tolerance = f64::INFINITY).contains("bond_tolerance"));
    let other = generate::grid(3, 3);
    let foreign = pipeline::tiles_for_pattern(
        &other,
        None,
        pattern.clone(),
        &spec,
        &FinishOptions::for_spec(&spec),
    )
    .unwrap_err();
    assert!(matches!(foreign, pipeline::Error::PatternMismatch { .. }));
    // A tile the wrong way round for the half-tile model is still placed and fitted.
    let ok = pipeline::tiles_for_pattern(
        &quads,
        None,
        pattern,
        &spec,
        &FinishOptions::for_spec(&spec),
    )
    .unwrap();
    assert!(ok.report.fit.is_some());
    let _: Option<TileError> = None;
}

#[test]
fn over_full_courses_of_a_dome_lose_a_closer_instead_of_tearing() {
    // The 3 m cap over 60 % of a sphere (issue 19): along the rim's courses its quads are
    // shorter than the tiles, the section 3.5 placement overlaps them by up to 152 mm, and a
    // fit that must slide every course's surplus to its ends tears the crown open. Courses
    // the first fit leaves overlapping or torn lose a closer per tile of surplus and are
    // fitted again. The greedy pattern (time limit 0) keeps the test deterministic; on it
    // the p95 deviation was 25.3 mm and 146 tiles were cut to fit without closers, 12.4 mm
    // and 98 with them.
    let tiling = greedy_cap_tiling();
    let joints = &tiling.report.joints;
    assert!(
        joints.p95_deviation <= 0.018,
        "p95 |gap - joint| {:.1} mm",
        joints.p95_deviation * 1000.0
    );
    assert!(
        joints.fit_cuts <= 120,
        "{} tiles cut to fit",
        joints.fit_cuts
    );
    assert!(joints.max_overlap <= 0.001);
}

/// The 3 m cap over 60 % of a sphere (issue 19) tiled by `run`'s pipeline with the greedy
/// pattern (time limit 0: deterministic however busy the machine).
fn greedy_cap_tiling() -> pipeline::Tiling {
    let cap = generate::spherical_cap(3.0, 0.6, 0.087);
    let options = {
        let mut o = PatternOptions::default();
        o.time_limit = Duration::ZERO;
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
    let finish = FinishOptions::for_spec(&SPEC);
    pipeline::tile_surface(
        &cap,
        &remesh,
        &options,
        &SPEC,
        &finish,
        &mut Control::none(),
    )
    .unwrap()
    .1
}

#[test]
fn the_tears_of_a_dome_are_filled_with_pieces_cut_to_the_room_left() {
    // Where the fit parts the cap's converging courses, pieces cut to the room left fill
    // the holes a piece's narrowest width fits in: coverage 0.935 without them, 0.969 with
    // them.
    let tiling = greedy_cap_tiling();
    let report = &tiling.report;
    let cutting = report.cutting.as_ref().expect("run cuts to the surface");
    assert!(cutting.coverage >= 0.96, "{}", cutting.coverage);
    assert!(report.joints.max_overlap <= 0.001);
}

#[test]
fn joints_that_cannot_close_gather_into_tears() {
    // On the cap's converging courses not every joint can close. A joint's cost that grows
    // only with the logarithm past two and a half joints gathers what cannot close into a
    // few tears, which take pieces, and closes the joints beside them; with Huber's loss
    // (linear past two joints) the misfit spread: 53 % of the joints within 2 mm of the
    // nominal one, 82 % within 5 mm, coverage 0.968; gathered 65 %, 86 %, 0.975.
    let tiling = greedy_cap_tiling();
    let joints = &tiling.report.joints;
    assert!(joints.within_2mm >= 0.6, "{}", joints.within_2mm);
    assert!(joints.within_5mm >= 0.84, "{}", joints.within_5mm);
    let cutting = tiling
        .report
        .cutting
        .as_ref()
        .expect("run cuts to the surface");
    assert!(cutting.coverage >= 0.972, "{}", cutting.coverage);
    assert!(joints.max_overlap <= 0.001);
}
