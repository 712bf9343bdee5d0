//! Tries: the whole pipeline run on a few quad meshes of the same surface, keeping the one
//! whose tiles fit best.
//!
//! Where the tiles can follow the quads without a dislocation (barrels, shallow domes, the
//! demo), every quad mesh gives the same tiles. Where they cannot (a bend, a hypar's
//! corners, a dome's rows converging), the cross field's cones and the lattice's row ends
//! can sit in many places of nearly the same energy, and which one the remesher settles on
//! decides where courses end, hence which tiles the fit must cut and how wide the joints
//! around them open. That choice is sensitive: on the tubemesh, renormalising the field
//! (paper section 3.1's smooth field, made of separate cones) half or twice as strongly as
//! the default moves its cones and gives p95 joint deviations of 4.2-5.2 mm and 2.1-3.8 %
//! of tiles cut. No measure of the quads alone predicts which is best (the count of
//! irregular vertices picks it on some shells and the worst on others; README, *Tries*),
//! so each quad mesh is carried through the pattern, the tiles and the fit, and judged by
//! what a mason meets: joints that need no look first (no `wide_joints` warning), then
//! cuts within issue 16's line (no `fit_cuts` warning: at most 1 % of the tiles cut by the
//! fit), then the fewest cut tiles, joints closest to the nominal one and most of the
//! surface covered ([`score`]).
//!
//! The first try renormalises at the given strength ([`RemeshOptions::renormalisation`]);
//! the second, where the field follows the curvature (the default: no direction, angle,
//! designer's field or guides asked for), orients the quads by the boundary and smoothness
//! alone ([`FieldDirection::Smooth`]) at that strength; the last two renormalise at twice
//! and half of it. Where the curvature lines converge (a cone's rulings, a funnel's or a
//! dome's rings, the tubemesh's bend) quads along them must end rows all over, and the
//! tiles there are cut; the smoothest field spreads that turning instead (`--tries 1` on 29
//! shells: a cone 62 -> 6 % of tiles cut, a funnel 20 -> 4 %, the tubemesh 3.2 -> 1.0 %;
//! worse on a 3 m spherical cap, 12 -> 22 %, where the first try stays). It comes second,
//! before the other strengths, as its gains are the larger and a later try whose pattern
//! reaches its time limit ends the tries. In level courses whose quads are raised to a
//! course's pitch (square quads longer than half a tile and a joint, [`TileSpec::quad_edge`])
//! a fifth try lays the smooth field's quads out for the courses, half a tile and a joint
//! along them and a pitch across ([`crate::remesh::CourseQuads`]): a course closed on itself
//! (a tower, a drum) then holds whole tiles at the nominal joint, and on 15 of 26 shells
//! (README, *Tries*) it fits best (the tubemesh 1.04 -> 0.43 % cut, the hypar's p95 3.2 ->
//! 1.5 mm); with the curvature's field, or on every try, the quads' two sizes disagree where
//! the crosses turn away from the level and it does worse as often as better
//! (docs/journal.md, *Lattices that favour the courses*). Where the first try follows a
//! boundary loop (one with corners, [`BoundaryAlignment::Auto`]) and the caller left the
//! alignment automatic, a sixth try lays the smooth field free of every loop: rows that
//! follow an edge curved on the surface converge as it does (the arcs of a conical vault, a
//! ring of a torus), where the free field is parallel on a developable surface and its rows
//! are cut to the edge (half a conical frustum: p95 1.6 -> 0.3 mm; README, *Free of the
//! boundary: a sixth try*). The first try is what one run gives, so tries never do worse by
//! the ranking. Each try is deterministic, so the kept one is too (ties go to the earlier
//! try).

use super::{Error, Tiling, tile_surface};
use crate::control::{Control, Figures};
use crate::mesh::PolyMesh;
use crate::pattern::{Courses, PatternOptions, SolveStatus};
use crate::remesh::{
    BoundaryAlignment, CourseQuads, FieldDirection, RemeshError, RemeshOptions, Remeshed,
};
use crate::report::warnings::WarningCode;
use crate::report::{Report, TryFigures};
use crate::tiles::{FinishOptions, FitStatus, TileSpec};

/// How many quad meshes [`tile_surface_tries`] carries through to tiles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Tries {
    /// [`MAX_TRIES`] when the surface needs at most [`AUTO_TRIES_QUADS`] quads, otherwise
    /// one: a few seconds more on a shell of a few thousand tiles, nothing more on a large
    /// one, where each run takes long and the pattern of thousands of courses averages out
    /// what one placement of the cones changes.
    #[default]
    Auto,
    /// This many, from 1 (one run, as [`tile_surface`]) to [`MAX_TRIES`].
    Count(usize),
}

impl Tries {
    /// How many tries [`tile_surface_tries`] makes on a surface of `area` with `remesh`,
    /// `options` and `spec`: as [`Tries::count`], less the smooth tries where the field does
    /// not follow the curvature alone and the courses' quads where there are none.
    pub fn count_for(
        self,
        area: f64,
        remesh: &RemeshOptions,
        options: &PatternOptions,
        spec: &TileSpec,
    ) -> usize {
        let courses = course_quads(remesh, options, spec);
        variants(
            remesh,
            courses.is_some(),
            self.count(area, remesh.target_edge),
        )
        .len()
    }

    /// How many tries on a surface of `area` remeshed at edge `t`.
    pub fn count(self, area: f64, t: f64) -> usize {
        match self {
            Tries::Count(n) => n.clamp(1, MAX_TRIES),
            Tries::Auto => {
                let quads = area / (t * t);
                if quads.is_finite() && quads <= AUTO_TRIES_QUADS {
                    MAX_TRIES
                } else {
                    1
                }
            }
        }
    }
}

/// Most tries: the strength given, the smooth field, twice and half the strength, the smooth
/// field's quads laid out for level courses, the smooth field free of the boundary.
pub const MAX_TRIES: usize = 6;

/// Quads (surface area over the target edge squared) up to which [`Tries::Auto`] tries
/// [`MAX_TRIES`] quad meshes: the shared dome's 6,300 quads run in about 5 s on 2 cores.
pub const AUTO_TRIES_QUADS: f64 = 10_000.0;

/// Time limit of a later try's pattern stage (the first has the caller's): ten times what
/// the level-course program of the largest surface tried takes to be proven here (the
/// shared dome's 6,300 quads, under a second). A later try whose pattern is not proven in
/// it is listed and not kept; one whose proof takes about this long may be kept on one
/// machine and not on a slower one.
pub const LATER_PATTERN_SECONDS: std::time::Duration = std::time::Duration::from_secs(10);

/// One try's quad mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Variant {
    /// Factor of the renormalisation strength.
    factor: f64,
    /// The field follows nothing ([`FieldDirection::Smooth`]) instead of the curvature.
    smooth: bool,
    /// Quads laid out for level courses ([`CourseQuads`]).
    along: bool,
    /// No boundary loop followed ([`BoundaryAlignment::Never`]) instead of those with
    /// corners.
    free_boundary: bool,
}

/// A try of the field's strength times `factor`, on the curvature, square quads, the
/// caller's boundary alignment.
const fn strength(factor: f64) -> Variant {
    Variant {
        factor,
        smooth: false,
        along: false,
        free_boundary: false,
    }
}

/// The quad meshes of the tries, in order.
const VARIANTS: [Variant; MAX_TRIES] = [
    strength(1.0),
    Variant {
        smooth: true,
        ..strength(1.0)
    },
    strength(2.0),
    strength(0.5),
    Variant {
        smooth: true,
        along: true,
        ..strength(1.0)
    },
    Variant {
        smooth: true,
        free_boundary: true,
        ..strength(1.0)
    },
];

/// Shortest quad edge along the courses, as a share of the edge across them, for which the
/// courses' quads are tried ([`course_quads`]): the pipeline's own quads for a tile of
/// length about twice its width (280 x 140 mm with a 10 mm joint: 145 / 150), not a target
/// edge the caller set far from half a tile.
const ALONG_SHARE: f64 = 0.8;

/// The courses' quads of the fifth try ([`VARIANTS`]): in level courses, half a tile and a
/// joint along them where that is shorter than `remesh`'s target edge (raised to a course's
/// pitch, [`TileSpec::quad_edge`]) by at most [`ALONG_SHARE`]; `None` otherwise.
fn course_quads(
    remesh: &RemeshOptions,
    options: &PatternOptions,
    spec: &TileSpec,
) -> Option<CourseQuads> {
    let Courses::Level { up } = options.courses else {
        return None;
    };
    let up = nalgebra::Vector3::from(up).try_normalize(0.0)?;
    let (along, t) = (spec.target_edge(), remesh.target_edge);
    (along.is_finite() && along < t && along >= ALONG_SHARE * t).then_some(CourseQuads {
        up: up.into(),
        along,
    })
}

/// The [`VARIANTS`] of the tries [`tile_surface_tries`] makes, at most `count` of them: a
/// smooth try only where the field would follow the curvature alone (a direction, an angle,
/// a designer's field or guide curves asked for are kept in every try), the courses' quads
/// only where there are some (`courses`, [`course_quads`]), the try free of the boundary
/// only where its alignment is automatic ([`tile_surface_tries`] skips it too where the
/// first try followed no loop).
fn variants(remesh: &RemeshOptions, courses: bool, count: usize) -> Vec<Variant> {
    let curvature_alone = remesh.direction == FieldDirection::Curvature && !remesh.designer_pulls();
    let boundary_auto = remesh.effective_boundary() == BoundaryAlignment::Auto;
    VARIANTS
        .into_iter()
        .filter(|v| {
            (!v.smooth || curvature_alone)
                && (!v.along || courses)
                && (!v.free_boundary || boundary_auto)
        })
        .take(count)
        .collect()
}

/// `remesh` as one of the [`variants`] asks for it, with the courses' quads `courses`.
fn variant_options(
    remesh: &RemeshOptions,
    variant: Variant,
    courses: Option<CourseQuads>,
) -> RemeshOptions {
    RemeshOptions {
        renormalisation: remesh.renormalisation * variant.factor,
        direction: if variant.smooth {
            FieldDirection::Smooth
        } else {
            remesh.direction
        },
        courses: courses.filter(|_| variant.along),
        boundary: if variant.free_boundary {
            BoundaryAlignment::Never
        } else {
            remesh.boundary
        },
        ..remesh.clone()
    }
}

/// What a try's field follows, as `report.json`'s `tries` name it.
fn field_name(direction: FieldDirection) -> &'static str {
    match direction {
        FieldDirection::Curvature => "curvature",
        FieldDirection::Smooth => "smooth",
        FieldDirection::Vector(_) => "direction",
        FieldDirection::Angle(_) => "angle",
    }
}

/// What the tiles of one try leave a mason, lower is better: the share of tiles cut to fit
/// or inside the fit's holes per percent, plus the p95 joint deviation per half joint, plus
/// the share of the surface left uncovered per percent, plus the pieces cut to the edge per
/// `EDGE_CUT_PERCENT` of the tiles. The first terms are in units of issue 16's line for
/// them (1 % cut, 5 mm on a 10 mm joint) or of a percent of the surface, so that one
/// percent more tiles cut weighs as much as half a joint wider p95 or one percent less
/// covered. With no joint the deviation counts per twentieth of the tile's width.
pub fn score(report: &Report) -> f64 {
    let unit = if report.tile.joint > 0.0 {
        0.5 * report.tile.joint
    } else {
        0.05 * report.tile.width
    };
    cut_share(report) / 0.01
        + report.joints.p95_deviation / unit
        + (1.0 - coverage(report)).max(0.0) / 0.01
        + edge_cut_share(report) / (EDGE_CUT_PERCENT * 0.01)
}

/// Percent of the tiles cut to the surface's edge that weighs as one percent cut to fit: a
/// mason cuts the pieces along an edge to one line, in series, and expects them, where each
/// cut to fit is a piece measured and cut where the courses fail to meet; but a try whose
/// rows meet an edge at a slant has a piece cut at every course's end where one following
/// the edge lays whole tiles. Four: the demo's shell keeps its rows along its edges (30
/// pieces cut at the edge, coverage 0.976) rather than the try free of the boundary (52
/// pieces, coverage 0.989), and a conical vault keeps the free try, which cuts fewer
/// (README, *Free of the boundary: a sixth try*).
const EDGE_CUT_PERCENT: f64 = 4.0;

/// Pieces cut to the surface's edge ([`Report::edge_cut_count`]) per full and half tile.
fn edge_cut_share(report: &Report) -> f64 {
    per_tile(report, report.edge_cut_count())
}

/// [`tile_surface`] on up to [`MAX_TRIES`] quad meshes of `surface` (see the module
/// documentation), keeping the tiles with the lowest [`score`] among those whose joints the
/// report does not flag (`wide_joints`), or among all when it flags every try: a few more
/// cut tiles are not bought with joints that need a look; and among those, first the tries
/// whose cuts it does not flag (`fit_cuts`, more than 1 % of the tiles): closer joints are
/// not bought with cuts beyond that line either (the tubemesh: 1.24 % cut at a p95 of 2.6
/// mm scores a little lower than 0.60 % at 4.5 mm, and the second is kept). The kept report lists every
/// try (`tries`) and which was kept (`chosen_try`). `control` hears each try as an equal
/// share of `0..1` and can cancel any.
///
/// A try whose pattern stage or fit reaches its time limit has tiles that depend on the
/// machine's speed: the first is compared all the same; a later one is listed but not kept
/// (`limit_reached`). Where each further try would take as long, the limit ends the tries
/// (`ended_tries`): always after a later try and the first try's fit, and after the first
/// try's pattern stage when its limit is no longer than a later try's
/// ([`LATER_PATTERN_SECONDS`]).
///
/// # Errors
/// As [`tile_surface`] for the first try, and [`RemeshError::Cancelled`] (or the pattern
/// stage's cancel) from any; a later try that fails otherwise (nothing extracted) is listed
/// and skipped.
pub fn tile_surface_tries(
    surface: &PolyMesh,
    remesh: &RemeshOptions,
    options: &PatternOptions,
    spec: &TileSpec,
    finish: &FinishOptions,
    tries: Tries,
    control: &mut Control<'_>,
) -> Result<(Remeshed, Tiling), Error> {
    // Counted on the input as given, as a caller counts them for the progress
    // (`Tries::count_for` with the input's area).
    let courses = course_quads(remesh, options, spec);
    let variants = variants(
        remesh,
        courses.is_some(),
        tries.count(surface.area(), remesh.target_edge),
    );
    let count = variants.len();
    let simplified = simplified_if_fine(surface, remesh, options, &mut || control.keep_going(0.0));
    let surface = simplified.as_ref().map_or(surface, |(mesh, _)| mesh);
    let mut listed: Vec<TryFigures> = Vec::with_capacity(count);
    let mut best: Option<(Rank, usize, Remeshed, Tiling)> = None;
    // Whether the first try's quads end rows all over the surface (see `pattern_limit`).
    let mut rows_end_everywhere = false;
    // Whether the first try followed a boundary loop: where it followed none, the try free
    // of the boundary would remesh as the smooth field's try did.
    let mut followed_boundary = true;
    for (k, &variant) in variants.iter().enumerate() {
        if variant.free_boundary && !followed_boundary {
            continue;
        }
        let options_k = variant_options(remesh, variant, courses);
        let started = std::time::Instant::now();
        let share = |fraction: f64| (k as f64 + fraction) / count as f64;
        // Each try's own figures: none before its pattern stage notes some.
        control.set_figures(None);
        let mut part = |fraction: f64, figures: Option<Figures>| {
            if let Some(figures) = figures {
                control.note(figures);
            }
            control.keep_going(share(fraction))
        };
        let pattern_k = PatternOptions {
            time_limit: pattern_limit(k, variant, rows_end_everywhere, options),
            ..options.clone()
        };
        let found = tile_surface(
            surface,
            &options_k,
            &pattern_k,
            spec,
            finish,
            &mut Control::with_figures(&mut part),
        );
        let seconds = started.elapsed().as_secs_f64();
        match found {
            Ok((remeshed, tiling)) => {
                if k == 0 {
                    rows_end_everywhere = remeshed.metrics.coarse_start;
                    followed_boundary = remeshed.metrics.aligned_boundary;
                }
                let r = &tiling.report;
                let value = score(r);
                let limit = limit_reached(r);
                let wide = r.warns(WarningCode::WideJoints);
                let many_cuts = r.warns(WarningCode::FitCuts);
                let ended_tries = limit.is_some_and(|stage| ends_tries(k, stage, options));
                listed.push(TryFigures {
                    renormalisation: options_k.renormalisation,
                    field: field_name(options_k.direction),
                    quads_along_courses: options_k.courses.is_some(),
                    boundary_free: variant.free_boundary,
                    quads: remeshed.quads.face_count(),
                    interior_irregular_vertices: remeshed.metrics.interior_irregular_vertices,
                    p95_deviation: r.joints.p95_deviation,
                    cut_share: cut_share(r),
                    coverage: coverage(r),
                    wide_joints: wide,
                    fit_cuts: many_cuts,
                    score: Some(value),
                    seconds,
                    limit_reached: limit,
                    ended_tries,
                    failed: None,
                });
                // A try stopped by a time limit gave tiles that depend on the machine's
                // speed: the first is compared all the same (it is what one run gives), a
                // later one is not; and no further try is made where each would take as
                // long (`TryFigures::ended_tries`).
                let rank: Rank = (wide, many_cuts, value);
                if (k == 0 || limit.is_none()) && best.as_ref().is_none_or(|(b, ..)| rank < *b) {
                    best = Some((rank, k, remeshed, tiling));
                }
                if ended_tries {
                    break;
                }
            }
            Err(e) if k == 0 || is_cancel(&e) => return Err(e),
            Err(e) => listed.push(TryFigures {
                renormalisation: options_k.renormalisation,
                field: field_name(options_k.direction),
                quads_along_courses: options_k.courses.is_some(),
                boundary_free: variant.free_boundary,
                quads: 0,
                interior_irregular_vertices: 0,
                p95_deviation: 0.0,
                cut_share: 0.0,
                coverage: 0.0,
                wide_joints: false,
                fit_cuts: false,
                score: None,
                seconds,
                limit_reached: None,
                ended_tries: false,
                failed: Some(e.to_string()),
            }),
        }
    }
    let (_, chosen, mut remeshed, mut tiling) = best.expect("the first try succeeded or returned");
    remeshed.metrics.input_vertices_removed = simplified.map_or(0, |(_, removed)| removed);
    if count > 1 {
        // Listed even when the first try's time limit left it alone: the report says why.
        tiling.report.tries = listed;
        tiling.report.chosen_try = Some(chosen);
    }
    Ok((remeshed, tiling))
}

/// An input whose mean edge is shorter than the quads' target edge divided by this is
/// simplified before the tries ([`simplified_if_fine`]).
const FINE_INPUT: f64 = 6.0;

/// `surface` simplified to edges of at most the target edge ([`crate::mesh::simplify`]) when
/// it is much finer than the quads ([`FINE_INPUT`]), with the vertices removed; `None` when
/// it is not, and when a designer's field or zones are given per vertex or face of it (they
/// would lose their vertices and faces). A surface of a million triangles at 8 mm, tiled
/// with 280 mm tiles, becomes one of about 7,000 vertices: each stage then works on those,
/// while every vertex kept is one of the input's and the boundary stays the input's. A cancel
/// (`keep_going` saying no) stops it with what it has; the first try then stops at once.
fn simplified_if_fine(
    surface: &PolyMesh,
    remesh: &RemeshOptions,
    options: &PatternOptions,
    keep_going: &mut dyn FnMut() -> bool,
) -> Option<(PolyMesh, usize)> {
    if remesh.user_field.is_some() || options.zones.is_some() {
        return None;
    }
    let p = surface.positions();
    let (mut length, mut edges) = (0.0, 0usize);
    for face in surface.faces() {
        for k in 0..face.len() {
            length += (p[face[(k + 1) % face.len()]] - p[face[k]]).norm();
            edges += 1;
        }
    }
    let t = remesh.target_edge;
    if edges == 0 || length / edges as f64 >= t / FINE_INPUT {
        return None;
    }
    let (mesh, removed) = crate::mesh::simplify::simplify(surface, t, keep_going);
    (removed > 0).then_some((mesh, removed))
}

/// Share of the surface the tiles cover (1 when the report has no cutting figures).
fn coverage(report: &Report) -> f64 {
    report.cutting.as_ref().map_or(1.0, |c| c.coverage)
}

/// Tiles cut by the fit ([`Report::fit_cut_count`]) per full and half tile.
fn cut_share(report: &Report) -> f64 {
    per_tile(report, report.fit_cut_count())
}

/// `count` per full and half tile of `report` (per one when there are none).
fn per_tile(report: &Report, count: usize) -> f64 {
    count as f64 / (report.full_tiles + report.half_tiles).max(1) as f64
}

/// The pattern stage's time limit of try `k` (from 0) of `variant`. The first try has the
/// caller's; a later one at most [`LATER_PATTERN_SECONDS`]: a quad mesh whose pattern is not
/// proven by then is not kept anyway, and would cost the whole limit (a minute by default)
/// for nothing. Except the smooth field's try when the first try's quads end rows all over
/// the surface (`rows_end_everywhere`, its lattice solved from the coarse start): there the
/// smooth field, which follows neither rings nor curvature, ends far fewer rows and its
/// pattern, proven in some seconds more than a later try has, is the one to keep (a bell:
/// 34.5 % of the tiles cut on the first try's quads, 6.4 % on the smooth field's, proven
/// in 12.9 s), so it gets the caller's limit too.
fn pattern_limit(
    k: usize,
    Variant { smooth, .. }: Variant,
    rows_end_everywhere: bool,
    options: &PatternOptions,
) -> std::time::Duration {
    if k == 0 || (smooth && rows_end_everywhere) {
        options.time_limit
    } else {
        options.time_limit.min(LATER_PATTERN_SECONDS)
    }
}

/// Whether try `k` (from 0), whose `stage` reached its time limit, ends the tries: where
/// each further try would take as long. A later try's pattern stage has a limit of its own,
/// [`LATER_PATTERN_SECONDS`], so after the first try's pattern stage with a longer limit
/// (`options`'), the later tries still run.
fn ends_tries(k: usize, stage: &str, options: &PatternOptions) -> bool {
    k > 0 || stage != "pattern" || options.time_limit <= LATER_PATTERN_SECONDS
}

/// The stage whose time limit a try reached, if any: the pattern stage's search, or the
/// fit's placement (or its tear fill). A fit the caller cancelled counts too: it keeps its
/// placement so far rather than failing (the other stages fail), and no further try is
/// made after it either.
fn limit_reached(report: &Report) -> Option<&'static str> {
    if report.status == SolveStatus::TimeLimit {
        Some("pattern")
    } else if report
        .fit
        .as_ref()
        .is_some_and(|f| matches!(f.status, FitStatus::TimeLimit | FitStatus::Cancelled))
    {
        Some("fit")
    } else {
        None
    }
}

/// How a try ranks, lower first: its joints flagged wide (`wide_joints`), its cuts flagged
/// (`fit_cuts`), its [`score`].
type Rank = (bool, bool, f64);

/// Whether `e` is the caller's cancel, which ends every try.
fn is_cancel(e: &Error) -> bool {
    matches!(
        e,
        Error::Remesh(RemeshError::Cancelled)
            | Error::Pattern(crate::pattern::PatternError::Cancelled)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;
    use crate::pattern::Courses;

    #[test]
    fn auto_tries_every_quad_mesh_on_a_shell_of_some_thousand_quads_and_one_on_a_large_one() {
        let t = 0.15;
        // 3 x 4 m: 533 quads; 20 m across: 17,778 quads.
        assert_eq!(Tries::Auto.count(12.0, t), MAX_TRIES);
        assert_eq!(Tries::Auto.count(400.0, t), 1);
        assert_eq!(Tries::Count(2).count(400.0, t), 2);
        assert_eq!(Tries::Count(0).count(1.0, t), 1);
        assert_eq!(Tries::Count(9).count(1.0, t), MAX_TRIES);
        assert_eq!(Tries::Auto.count(f64::NAN, t), 1);
        // The smooth tries only where the field would follow the curvature alone, the
        // courses' quads only in level courses with quads of a course's pitch.
        let (spec, level, mut remesh) = level_courses();
        assert!((remesh.target_edge - t).abs() < 1e-12);
        let free = PatternOptions::default();
        assert_eq!(
            Tries::Auto.count_for(12.0, &remesh, &level, &spec),
            MAX_TRIES
        );
        assert_eq!(
            Tries::Auto.count_for(12.0, &remesh, &free, &spec),
            MAX_TRIES - 1
        );
        let courses = course_quads(&remesh, &level, &spec).expect("level courses");
        assert_eq!(
            (courses.up, courses.along),
            ([0.0, 0.0, 1.0], spec.target_edge())
        );
        let along: Vec<bool> = variants(&remesh, true, MAX_TRIES)
            .into_iter()
            .map(|v| variant_options(&remesh, v, Some(courses)).courses.is_some())
            .collect();
        assert_eq!(along, [false, false, false, false, true, false]);
        // The last try follows no boundary loop; a caller's own alignment is kept in every
        // try, and then there is none free of it.
        let boundary: Vec<BoundaryAlignment> = variants(&remesh, true, MAX_TRIES)
            .into_iter()
            .map(|v| variant_options(&remesh, v, Some(courses)).boundary)
            .collect();
        let (auto, never) = (BoundaryAlignment::Auto, BoundaryAlignment::Never);
        assert_eq!(boundary, [auto, auto, auto, auto, auto, never]);
        for given in [BoundaryAlignment::Always, BoundaryAlignment::Never] {
            let followed = RemeshOptions {
                boundary: given,
                ..remesh.clone()
            };
            let tried: Vec<BoundaryAlignment> = variants(&followed, true, MAX_TRIES)
                .into_iter()
                .map(|v| variant_options(&followed, v, Some(courses)).boundary)
                .collect();
            assert_eq!(tried, [given; MAX_TRIES - 1], "{given:?}");
        }
        // Quads at half a tile already (a target edge the caller gave), or far from it: none.
        for edge in [spec.target_edge(), 0.2] {
            let given = RemeshOptions {
                target_edge: edge,
                ..remesh.clone()
            };
            assert!(course_quads(&given, &level, &spec).is_none(), "{edge}");
        }
        remesh.direction = FieldDirection::Vector([1.0, 0.0, 0.0]);
        assert_eq!(
            Tries::Auto.count_for(12.0, &remesh, &level, &spec),
            MAX_TRIES - 3
        );
        let fields: Vec<_> = variants(&remesh, true, MAX_TRIES)
            .into_iter()
            .map(|v| field_name(variant_options(&remesh, v, Some(courses)).direction))
            .collect();
        assert_eq!(fields, ["direction"; MAX_TRIES - 3]);
    }

    /// The 280 x 140 x 15 mm tile with a 10 mm joint in metres, level courses and the quads
    /// for them.
    fn level_courses() -> (TileSpec, PatternOptions, RemeshOptions) {
        let spec = TileSpec {
            length: 0.28,
            width: 0.14,
            thickness: 0.015,
            joint: 0.01,
        };
        let options = PatternOptions {
            courses: Courses::Level {
                up: [0.0, 0.0, 1.0],
            },
            ..PatternOptions::default()
        };
        let remesh = RemeshOptions {
            target_edge: spec.quad_edge(true),
            ..RemeshOptions::default()
        };
        (spec, options, remesh)
    }

    #[test]
    fn on_a_cone_the_smooth_try_is_kept() {
        // A cone 5 m across and 1.25 m high: its curvature lines, the rulings and the rings,
        // converge on the apex, and square quads along them must end rows all over.
        let surface = generate::cone(2.5, 1.25, 0.1);
        let (spec, options, remesh) = level_courses();
        let (quads, tiling) = tile_surface_tries(
            &surface,
            &remesh,
            &options,
            &spec,
            &FinishOptions::for_spec(&spec),
            Tries::Auto,
            &mut Control::none(),
        )
        .unwrap();
        let r = &tiling.report;
        let fields: Vec<&str> = r.tries.iter().map(|x| x.field).collect();
        assert_eq!(
            fields,
            ["curvature", "smooth", "curvature", "curvature", "smooth"]
        );
        let strengths: Vec<f64> = r.tries.iter().map(|x| x.renormalisation).collect();
        assert_eq!(strengths, [0.5, 0.5, 1.0, 0.25, 0.5]);
        // Its round rim has no corner: no try follows it, so none is made free of it.
        assert!(!quads.metrics.aligned_boundary);
        assert!(r.tries.iter().all(|x| !x.boundary_free));
        println!("{:?}", r.tries);
        // The smooth field's quads (square, or laid out for the courses) are near the tile's
        // size, with rows that end nowhere inside, and the tiles on them are hardly cut.
        assert!(matches!(r.chosen_try, Some(1 | 4)), "{:?}", r.chosen_try);
        assert_eq!(quads.metrics.interior_irregular_vertices, 0);
        assert!(quads.metrics.edges_within_20pct > 0.85);
        assert!(cut_share(r) < 0.02, "{}", cut_share(r));
        assert!(coverage(r) > 0.97, "{}", coverage(r));
        assert!(!r.warns(WarningCode::WideJoints));
    }

    #[test]
    fn an_input_much_finer_than_the_quads_is_tiled_simplified_and_as_well() {
        let (spec, options, remesh) = level_courses();
        let shell =
            |edge| generate::triangulate_quads(&generate::corner_supported_shell(3.0, edge));
        // 15 mm triangles, a tenth of the quads' edge: simplified; 50 mm: as given.
        let (fine, usual) = (shell(0.015), shell(0.05));
        let (simplified, removed) =
            simplified_if_fine(&fine, &remesh, &options, &mut || true).unwrap();
        assert!(removed * 10 > fine.positions().len() * 9, "{removed}");
        assert!((simplified.area() - fine.area()).abs() < 1e-3 * fine.area());
        assert!(simplified_if_fine(&usual, &remesh, &options, &mut || true).is_none());
        // Not where zones are given per face of the input.
        let zoned = PatternOptions {
            zones: Some(vec![crate::pattern::Bond::Stack; fine.face_count()]),
            ..options.clone()
        };
        assert!(simplified_if_fine(&fine, &remesh, &zoned, &mut || true).is_none());
        // The fine input's tiles are as good as the usual one's, and the report says so.
        let run = |surface: &PolyMesh| {
            tile_surface_tries(
                surface,
                &remesh,
                &options,
                &spec,
                &FinishOptions::for_spec(&spec),
                Tries::Count(1),
                &mut Control::none(),
            )
            .unwrap()
        };
        let ((fine_quads, fine_tiles), (usual_quads, usual_tiles)) = (run(&fine), run(&usual));
        assert_eq!(fine_quads.metrics.input_vertices_removed, removed);
        assert_eq!(usual_quads.metrics.input_vertices_removed, 0);
        let (a, b) = (&fine_tiles.report, &usual_tiles.report);
        assert!(
            (a.full_tiles as f64 - b.full_tiles as f64).abs() <= 0.02 * b.full_tiles as f64,
            "{} {}",
            a.full_tiles,
            b.full_tiles
        );
        assert!(
            coverage(a) > coverage(b) - 0.01,
            "{} {}",
            coverage(a),
            coverage(b)
        );
        assert!(a.joints.p95_deviation < 2e-3, "{}", a.joints.p95_deviation);
    }

    /// A small dome (umbilic, so where its field's cones sit is up to the renormalisation)
    /// with the 280 x 140 x 15 mm tile and a 10 mm joint, in metres.
    fn small_dome() -> (PolyMesh, TileSpec) {
        let spec = TileSpec {
            length: 0.28,
            width: 0.14,
            thickness: 0.015,
            joint: 0.01,
        };
        (generate::spherical_cap(1.2, 0.4, 0.06), spec)
    }

    /// The small dome's tiles from three tries with `options`, its remesh options for them
    /// and the finish options.
    fn three_tries(
        options: &PatternOptions,
    ) -> (PolyMesh, TileSpec, RemeshOptions, Remeshed, Tiling) {
        let (surface, spec) = small_dome();
        let remesh = RemeshOptions {
            target_edge: spec.quad_edge(options.courses != Courses::Free),
            ..RemeshOptions::default()
        };
        let (quads, tiling) = tile_surface_tries(
            &surface,
            &remesh,
            options,
            &spec,
            &FinishOptions::for_spec(&spec),
            Tries::Count(3),
            &mut Control::none(),
        )
        .unwrap();
        (surface, spec, remesh, quads, tiling)
    }

    #[test]
    fn the_kept_tiles_are_the_try_with_the_lowest_score_and_the_first_try_is_one_run() {
        let options = PatternOptions {
            courses: Courses::Level {
                up: [0.0, 0.0, 1.0],
            },
            ..PatternOptions::default()
        };
        let (surface, spec, remesh, quads, tiling) = three_tries(&options);
        let r = &tiling.report;
        assert_eq!(r.tries.len(), 3);
        let ranks: Vec<(bool, bool, f64)> = r
            .tries
            .iter()
            .map(|x| (x.wide_joints, x.fit_cuts, x.score.unwrap()))
            .collect();
        println!("{:?}", r.tries);
        let chosen = r.chosen_try.unwrap();
        assert!(ranks.iter().all(|x| *x >= ranks[chosen]), "{ranks:?}");
        assert!(
            ranks[..chosen].iter().all(|x| *x > ranks[chosen]),
            "ties go to the earlier try"
        );
        assert_eq!(score(r), ranks[chosen].2);
        assert_eq!(r.warns(WarningCode::WideJoints), ranks[chosen].0);
        assert_eq!(r.warns(WarningCode::FitCuts), ranks[chosen].1);
        assert_eq!(quads.quads.face_count(), r.tries[chosen].quads);
        let strengths: Vec<f64> = r.tries.iter().map(|x| x.renormalisation).collect();
        assert_eq!(strengths, [0.5, 0.5, 1.0]);
        let fields: Vec<&str> = r.tries.iter().map(|x| x.field).collect();
        assert_eq!(fields, ["curvature", "smooth", "curvature"]);
        // The first try is what one run gives.
        let (_, one) = super::super::tile_surface(
            &surface,
            &remesh,
            &options,
            &spec,
            &FinishOptions::for_spec(&spec),
            &mut Control::none(),
        )
        .unwrap();
        assert_eq!(score(&one.report), ranks[0].2);
        assert!(one.report.tries.is_empty() && one.report.chosen_try.is_none());
    }

    #[test]
    fn a_try_stopped_by_its_time_limit_ends_the_tries() {
        // No time for the pattern stage: its greedy start, stopped by the limit, on every try.
        // A limit no longer than a later try's ends the tries at the first.
        let options = PatternOptions {
            time_limit: std::time::Duration::ZERO,
            ..PatternOptions::default()
        };
        let (.., tiling) = three_tries(&options);
        let r = &tiling.report;
        assert_eq!(r.status, SolveStatus::TimeLimit);
        assert_eq!(r.tries.len(), 1, "{:?}", r.tries);
        assert_eq!(r.tries[0].limit_reached, Some("pattern"));
        assert!(r.tries[0].ended_tries);
        assert_eq!(r.chosen_try, Some(0));
    }

    #[test]
    fn the_smooth_try_gets_the_callers_pattern_limit_only_where_rows_end_everywhere() {
        let options = PatternOptions {
            time_limit: std::time::Duration::from_secs(60),
            ..PatternOptions::default()
        };
        let full = options.time_limit;
        assert_eq!(pattern_limit(0, VARIANTS[0], false, &options), full);
        assert_eq!(pattern_limit(1, VARIANTS[1], true, &options), full);
        assert_eq!(
            pattern_limit(1, VARIANTS[1], false, &options),
            LATER_PATTERN_SECONDS
        );
        assert_eq!(
            pattern_limit(2, VARIANTS[2], true, &options),
            LATER_PATTERN_SECONDS
        );
    }

    #[test]
    fn only_the_first_pattern_stage_with_a_longer_limit_than_later_ones_lets_the_tries_go_on() {
        let with = |seconds: u64| PatternOptions {
            time_limit: std::time::Duration::from_secs(seconds),
            ..PatternOptions::default()
        };
        let long = with(60);
        assert!(!ends_tries(0, "pattern", &long));
        assert!(ends_tries(0, "fit", &long));
        assert!(ends_tries(1, "pattern", &long));
        assert!(ends_tries(2, "fit", &long));
        assert!(ends_tries(0, "pattern", &with(10)));
        assert!(ends_tries(0, "pattern", &with(5)));
    }
}
