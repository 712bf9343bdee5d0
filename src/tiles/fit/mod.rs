//! Stage 3b: the fit. Moves every placed tile as a rigid body on the surface so that the
//! joints between neighbours come close to the mortar joint, keeping the bond.
//!
//! The paper places each tile on its pair of quads (section 3.5) and notes what follows
//! where quads are not the half tile's size (section 3.1, Figure 3): "overlapping tiles", and
//! gaps that grow with curvature (section 4.1, Figure 8). Its cure, "an optimisation step
//! after the variable quadrangulation to find a tileable mesh" (section 4.3), is this stage,
//! done on the tiles instead of the mesh: a tile is rigid, so it is the tiles that must fit,
//! and a mason adjusts the same way, sliding tiles along their course and spreading a
//! course's leftover over its head joints.
//!
//! Each tile keeps its origin on the surface (the closest point) and its thickness axis
//! along the surface's normal there, and may slide and turn in its tangent plane
//! ([`solve`]). Where that first placement leaves a course overlapping or torn, the course
//! loses a closer per tile of surplus and the rest is placed again ([`closers`]). Where it
//! leaves a room about a half tile (or a tile) long between two heads of a course, a whole
//! piece is laid there and the tiles placed again around it ([`rooms`]); a tear too narrow
//! for a piece is pulled shut along its course where the course has slack ([`close`]).
//! What cannot be made to fit is not left overlapping: after the tiles are cut to the
//! boundary, [`resolve_overlaps`] cuts the rest, closers first (rarely: the method's aim is
//! to cut little).

mod close;
mod closers;
pub(crate) mod contacts;
mod cuts;
mod rooms;
mod solve;

pub(crate) use cuts::cut_to_room;
pub use cuts::{resolve_overlaps, resolve_overlaps_nudging};

use std::time::Instant;

use serde::Serialize;

use crate::control::Control;
use crate::geom::SurfaceIndex;
use crate::mesh::{PolyMesh, Topology};
use crate::pattern::Bond;
use crate::tiles::{Tile, TileError, TileSpec};

use self::solve::{BondBand, Problem, Weights};

/// Residual weights: an overlap counts four times a gap of the same size per millimetre
/// (sixteen times squared); a joint narrower than the nominal one twice (four times
/// squared: the mortar fills a wider joint, and a wedge-shaped joint then keeps its narrow
/// end a fifth of the wedge under the joint instead of half of it; measured with
/// `fit_losses` and on shells not tuned on, README *Fit stage*: the tubemesh's p95
/// deviation 7.8 -> 5.3 mm, the dome's 2.6 -> 1.3, a squashed vault's 8.9 -> 6.6; at 1.5 or
/// 3 instead of 2 the p95 is higher everywhere but on the hypar); a bond band as much as a
/// joint; a tile's overhang beyond the surface's edge a quarter (where the quads' outer row
/// is narrower than a course, that course overhangs rather than squeezing every joint
/// inside: measured on the shared vault, weight 4 keeps 0.4 % more tiles on the surface
/// with p95 joint deviations of 7 mm instead of 2.6 mm); the anchor a thousandth, so that
/// it only settles what the joints leave free.
/// `wide` and `tear` are set per tile spec ([`wide_gap`], [`TEAR_FROM`]).
const WEIGHTS: Weights = Weights {
    overlap_slope: 4.0,
    narrow_slope: 2.0,
    bond: 1.0,
    anchor: 1e-3,
    edge: 0.25,
    wide: 0.0,
    tear: f64::INFINITY,
};

/// p95 of |gap - joint| as a share of the joint above which the joints are flagged (5 mm on
/// a 10 mm joint; the report's `wide_joints` warning), and above which the fit's first
/// placement is tried again with closers taken out ([`closers`]).
pub const MAX_P95_DEVIATION_SHARE: f64 = 0.5;

/// Tile steps (one tile through one step of a placement) the fit takes per second on a
/// reference machine: 2 cores of 2026, where the 20 m cap's first placement (17,311 tiles,
/// 86 steps) took 4.2 s.
///
/// The second placement, with closers taken out ([`closers`]), starts again from the
/// anchors and costs about as much as the first, so it is begun only when the first's tile
/// steps are at most a quarter of what the fit's time limit allows at this rate: both then
/// finish within the limit on a machine half as fast. A count of work, not the clock, so
/// that the same input and options give the same tiles on any machine (the time limit still
/// stops a placement, and the status says so). With the default 10 s that is 875k tile
/// steps: the 3 m cap's 61k (1598 tiles, 38 steps; the one flagged run of 2026-12-05 where
/// the second placement is kept) is tried, the 20 m cap's 1.5 M is not (there the second
/// ran to its step limit and was dropped, after 4.4 s).
const TILE_STEPS_PER_SECOND: f64 = 350_000.0;

/// Whether a second placement may follow a first of `tiles` tiles and `steps` steps within
/// a fit time limit of `time_limit` seconds ([`TILE_STEPS_PER_SECOND`]).
fn second_placement_fits(tiles: usize, steps: usize, time_limit: f64) -> bool {
    tiles as f64 * steps as f64 <= TILE_STEPS_PER_SECOND * time_limit / 4.0
}

/// How much wider than the joint a gap may be before its cost grows only linearly: the joint
/// itself (a gap of twice the joint is where courses part rather than a joint to close), a
/// tenth of the tile's width without a joint. Measured on the shared surfaces and on
/// QuadriFlow quad meshes of them (README, fit stage): the tiles cut to fit fall from 58 to
/// 36 on the tubemesh and from 19 to 13 and 15 to 7 on QuadriFlow's tubemesh and dome.
fn wide_gap(spec: &TileSpec) -> f64 {
    if spec.joint > 0.0 {
        spec.joint
    } else {
        spec.width / 10.0
    }
}

/// The residual weights for a tile spec: [`WEIGHTS`] with `wide` and `tear` set from it.
fn weights_for(spec: &TileSpec) -> Weights {
    Weights {
        wide: wide_gap(spec),
        tear: TEAR_FROM * wide_gap(spec),
        ..WEIGHTS
    }
}

/// How wide a gap is when it is no joint but a tear the fill will take a cut piece for:
/// the joint and two [`wide_gap`]s (30 mm on a 10 mm joint).
fn tear_gap(spec: &TileSpec) -> f64 {
    spec.joint + 2.0 * wide_gap(spec)
}

/// Where a joint's cost turns from Huber's linear growth to a logarithm's
/// ([`solve`]'s `capped`), in [`wide_gap`]s beyond the joint: 1.5 (a 25 mm gap on a 10 mm
/// joint), so that joints that cannot close gather into tears that take a piece. Measured
/// on 51 runs (the shared surfaces, domes triangulated four ways, cross vaults, sails,
/// saddles and barrels at 260, 280 and 300 mm tiles; docs/journal.md *Joints that cannot close
/// become tears*): the summed p95 deviation 250 -> 198 mm, tiles cut to fit 330 -> 186; at
/// 1 and 2 the domes gain as much but the tubemesh loses (p95 5.0 -> 6.6 mm at 1), at 3
/// the domes gain less.
const TEAR_FROM: f64 = 1.5;

/// How the fit stage places tiles.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FitOptions {
    /// The bond to keep: its offsets between courses bound how far tiles may slide.
    pub bond: Bond,
    /// For the running bond, how far the half offset between courses may stray; for stack
    /// bond (and continuous joints of the others), how far aligned joints may; model units.
    pub bond_tolerance: f64,
    /// Overlaps up to this depth are left (the mortar takes them); deeper ones are cut.
    /// Model units.
    pub overlap_tolerance: f64,
    /// Wall-clock seconds for the placement; when they run out the best placement so far is
    /// kept and the status says so. The pipeline gives the fill of the fit's tears the same
    /// limit again ([`crate::tiles::finish_with`]). It also sizes, by a count of work and not
    /// by the clock, the largest first placement after which a second is tried
    /// ([`TILE_STEPS_PER_SECOND`]).
    pub time_limit: f64,
    /// Most Levenberg-Marquardt steps.
    pub max_iterations: usize,
}

impl FitOptions {
    /// Defaults for a tile: the staggered bond, a bond tolerance of a tenth of the tile's
    /// length, overlaps up to a twentieth of the joint left (0.5 mm on a 10 mm joint), or
    /// a three-hundredth of the width where that is more (0.47 mm on a 140 mm tile, within
    /// what a tile's own size varies: with no joint at all, a tolerance of a thousandth of
    /// the width cut 17 % of a shell's tiles for overlaps of 0.2 mm), 10 s, 100 steps.
    pub fn for_spec(spec: &TileSpec) -> Self {
        let overlap_tolerance = (spec.joint / 20.0).max(spec.width / 300.0);
        Self {
            bond: Bond::Staggered {
                weight: crate::pattern::DEFAULT_WEIGHT,
            },
            bond_tolerance: spec.length / 10.0,
            overlap_tolerance,
            time_limit: 10.0,
            max_iterations: 100,
        }
    }

    /// Checks that tolerances and the time limit are finite and not negative.
    ///
    /// # Errors
    /// [`TileError::InvalidSpec`] naming the first bad value.
    pub fn validate(&self) -> Result<(), TileError> {
        let values = [
            ("fit_bond_tolerance", self.bond_tolerance),
            ("fit_overlap_tolerance", self.overlap_tolerance),
            ("fit_time_limit_seconds", self.time_limit),
        ];
        for (name, value) in values {
            if !(value.is_finite() && value >= 0.0) {
                return Err(TileError::InvalidSpec { name, value });
            }
        }
        Ok(())
    }
}

/// How the fit ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum FitStatus {
    /// Further steps no longer improved the joints.
    Converged,
    /// The step limit was reached first.
    IterationLimit,
    /// The time limit was reached first: the best placement so far is kept.
    TimeLimit,
    /// The caller cancelled: the best placement so far is kept.
    Cancelled,
}

/// What the fit did.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FitSummary {
    /// How it ended.
    pub status: FitStatus,
    /// Levenberg-Marquardt steps taken (of both placements when closers were taken out).
    pub iterations: usize,
    /// Sum of squared joint, bond and anchor residuals (model units squared) before and
    /// after.
    pub objective_before: f64,
    /// The same after the fit.
    pub objective_after: f64,
    /// Mean distance a tile's origin moved from the section 3.5 placement.
    pub mean_move: f64,
    /// Largest such distance.
    pub max_move: f64,
    /// Overlaps up to this depth were left, deeper ones cut ([`FitOptions::overlap_tolerance`]).
    pub overlap_tolerance: f64,
    /// Standard pieces (halves, or whole tiles) laid in rooms the placement left between the
    /// heads of a course, each with its joints within [`MAX_P95_DEVIATION_SHARE`] of the
    /// joint ([`rooms`]): among the tiles with no faces, in the cut list's whole blanks
    /// (labels F and H), no cut on site.
    pub room_pieces: usize,
    /// Tears too narrow for a standard piece that the fit closed by pressing the head joints
    /// of their courses ([`close`]): no piece cut for them.
    pub closed_tears: usize,
}

/// Moves `tiles` (as built by [`crate::tiles::build`] on `quads`) to fit their joints,
/// keeping them on `surface` (the quad mesh when `None`). Every tile keeps its faces, kind
/// and size; only its frame and corners change. `control` hears the share of the step limit
/// used and may cancel (the placement so far is returned).
///
/// # Errors
/// Invalid options, or tiles that do not belong to `quads`.
pub fn fit(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    tiles: Vec<Tile>,
    spec: &TileSpec,
    options: &FitOptions,
    control: &mut Control<'_>,
) -> Result<(Vec<Tile>, FitSummary), TileError> {
    let started = Instant::now();
    spec.validate()?;
    options.validate()?;
    for tile in &tiles {
        if let Some(&face) = tile.faces.iter().find(|&&f| f >= quads.face_count()) {
            return Err(TileError::FaceOutOfRange {
                face,
                face_count: quads.face_count(),
            });
        }
    }
    let topology = Topology::new(quads).expect("a PolyMesh is manifold by construction");
    let all = contacts::contacts(quads, &topology, &tiles);
    let index = SurfaceIndex::from_polymesh(surface.unwrap_or(quads));
    let (anchors, beyond_start): (Vec<_>, Vec<_>) = tiles
        .iter()
        .map(|t| solve::place(&index, &t.frame.origin.coords, &t.frame.x, &t.frame.z))
        .unzip();
    let sizes: Vec<[f64; 3]> = tiles.iter().map(|t| t.size).collect();
    let weights = weights_for(spec);
    let mut timed_out = false;
    // One placement from the anchors with the joints of `found`, reporting progress from
    // `from` to `to`.
    let mut place = |found: &[contacts::Contact], from: f64, to: f64| {
        let bands: Vec<Option<BondBand>> = found
            .iter()
            .map(|c| bond_band(c, &tiles, &anchors, spec, options))
            .collect();
        let problem = Problem {
            sizes: &sizes,
            contacts: found,
            bands: &bands,
            anchors: &anchors,
            beyond_start: &beyond_start,
            joint: spec.joint,
            weights,
            surface: &index,
            closing: &[],
        };
        let mut frames = anchors.clone();
        let outcome = problem.solve(&mut frames, options.max_iterations, &mut |fraction| {
            if started.elapsed().as_secs_f64() > options.time_limit {
                timed_out = true;
                return false;
            }
            control.keep_going(from + (to - from) * fraction)
        });
        (frames, outcome)
    };
    let (mut frames, first) = place(&all, 0.0, 0.6);
    let mut outcome = first;
    // Courses the first placement could not fit lose their closers and the rest is placed
    // again; not begun after a large first placement (the second would cost as much).
    let large = !second_placement_fits(tiles.len(), first.iterations, options.time_limit);
    let first_gaps = closers::gaps(&tiles, &frames, &all);
    // Closers only where the joints would be flagged: elsewhere the fit copes (and a large
    // shell's second placement would double its time).
    let flagged =
        closers::p95_deviation_after_cuts(&first_gaps, spec.joint, options.overlap_tolerance)
            > MAX_P95_DEVIATION_SHARE * spec.joint;
    let mut out = if first.stopped || large || !flagged {
        Vec::new()
    } else {
        let tear = tear_gap(spec);
        let failing = closers::failing(
            tiles.len(),
            &all,
            &first_gaps,
            options.overlap_tolerance,
            tear,
        );
        closers::closers(&tiles, &all, spec, &failing)
    };
    if !out.is_empty() {
        let found: Vec<contacts::Contact> = all
            .iter()
            .filter(|c| c.tiles.iter().all(|t| out.binary_search(t).is_err()))
            .copied()
            .collect();
        let (again, second) = place(&found, 0.6, 1.0);
        // Kept only when its joints, as the cuts to fit will leave them (closers at their
        // place and cut where they overlap), are no further from the joint than the first
        // placement's: closers where a course is torn by singularities rather than
        // over-full only add cuts.
        let better = || {
            let deviation = |gaps: &[f64]| {
                closers::p95_deviation_after_cuts(gaps, spec.joint, options.overlap_tolerance)
            };
            deviation(&closers::gaps(&tiles, &again, &all)) <= deviation(&first_gaps)
        };
        if second.stopped {
            // Cut short (time limit, cancel): the first placement, whole, is the better one.
            out.clear();
            outcome.stopped = true;
        } else if !better() {
            out.clear();
            outcome.iterations += second.iterations;
        } else {
            frames = again;
            outcome = solve::Progress {
                iterations: first.iterations + second.iterations,
                start: first.start,
                ..second
            };
        }
    }
    // Rooms about a standard piece long between the heads of a course take one, and the
    // placement is done again from where it is, so that the course's joints close around
    // it ([`rooms`]).
    let original = tiles.len();
    let mut closed_tears = 0;
    let mut placement = rooms::Placement {
        contacts: all
            .iter()
            .filter(|c| c.tiles.iter().all(|t| out.binary_search(t).is_err()))
            .copied()
            .collect(),
        tiles,
        frames,
        anchors,
        beyond_start,
        sizes,
    };
    if !outcome.stopped {
        // Rounds begun while the fit's work and theirs would fit in a third of the time limit
        // ([`TILE_STEPS_PER_SECOND`]): on a machine half as fast they still finish in time,
        // and the largest shells (the 20 m cap: 17,311 tiles, 52 steps before them, a round
        // of up to 40 more) keep their time (issue 19's 30 s for the whole run) unless the
        // designer gives the fit more (`--fit-time-limit 30`: its second placement, tried and
        // not kept, and rooms; 9.2 -> 8.7 % of its tiles cut, the fit 4.2 -> 12 s).
        let budget = (TILE_STEPS_PER_SECOND * options.time_limit / 3.0) as usize;
        let mut work = original * outcome.iterations;
        let setting = rooms::Setting {
            spec,
            options,
            weights,
            surface: &index,
        };
        let mut keep_going = |_| {
            if started.elapsed().as_secs_f64() > options.time_limit {
                timed_out = true;
                return false;
            }
            control.keep_going(1.0)
        };
        let laid = rooms::lay(
            &mut placement,
            &out,
            &setting,
            (&mut work, budget),
            &mut keep_going,
        );
        outcome.iterations += laid.iterations;
        outcome.stopped |= laid.stopped;
        if let Some(end) = laid.end {
            outcome.end = end;
        }
        // Then tears too narrow for a piece are closed along their courses ([`close`]).
        if !outcome.stopped {
            let closed = close::close(
                &mut placement,
                &out,
                &setting,
                (&mut work, budget),
                &mut keep_going,
            );
            outcome.iterations += closed.iterations;
            outcome.stopped |= closed.stopped;
            closed_tears = closed.tears;
            if let Some(end) = closed.end {
                outcome.end = end;
            }
        }
    }
    let rooms::Placement { tiles, frames, .. } = placement;
    let room_pieces = tiles.len() - original;
    let status = match (outcome.stopped, timed_out, outcome.converged) {
        (true, true, _) => FitStatus::TimeLimit,
        (true, false, _) => FitStatus::Cancelled,
        (false, _, true) => FitStatus::Converged,
        (false, _, false) => FitStatus::IterationLimit,
    };
    // Of the tiles of the pattern (the rooms' pieces had no place before the fit).
    let moves: Vec<f64> = tiles[..original]
        .iter()
        .zip(&frames)
        .map(|(t, f)| (f.origin - t.frame.origin).norm())
        .collect();
    let placed: Vec<Tile> = tiles
        .into_iter()
        .zip(frames)
        .enumerate()
        .map(|(i, (t, frame))| {
            let mut tile = Tile::new(t.kind, t.faces, frame, t.size);
            tile.fit_cut = out.binary_search(&i).is_ok();
            tile
        })
        .collect();
    let summary = FitSummary {
        status,
        iterations: outcome.iterations,
        objective_before: outcome.start,
        objective_after: outcome.end,
        mean_move: moves.iter().sum::<f64>() / moves.len().max(1) as f64,
        max_move: moves.iter().copied().fold(0.0, f64::max),
        overlap_tolerance: options.overlap_tolerance,
        room_pieces,
        closed_tears,
    };
    if status != FitStatus::Cancelled {
        control.keep_going(1.0);
    }
    Ok((placed, summary))
}

/// The band of centre offsets a bed joint between two full tiles may take: around the
/// offset the quads give it (none, or half a tile), a quarter tile either way in a
/// staggered bond (head joints of neighbouring courses stay a quarter tile apart),
/// `bond_tolerance` for the running bond's half offset and for aligned joints.
fn bond_band(
    contact: &contacts::Contact,
    tiles: &[Tile],
    frames: &[crate::tiles::Frame],
    spec: &TileSpec,
    options: &FitOptions,
) -> Option<BondBand> {
    let [a, b] = contact.tiles;
    let full = |t: usize| tiles[t].faces.len() == 2;
    if !(contact.sides[0].is_long() && contact.sides[1].is_long() && full(a) && full(b)) {
        return None;
    }
    let along = frames[a].z.cross(&contact.sides[0].normal(&frames[a]));
    let offset = along.dot(&(frames[b].origin - frames[a].origin));
    let half = (spec.length + spec.joint) / 2.0;
    let nominal = (offset / half).round().clamp(-1.0, 1.0) * half;
    let tolerance = match (options.bond, nominal == 0.0) {
        (_, true)
        | (
            Bond::RunningBond { .. }
            | Bond::Stack
            | Bond::Herringbone { .. }
            | Bond::BasketWeave { .. },
            false,
        ) => options.bond_tolerance,
        (Bond::Staggered { .. }, false) => half - spec.length / 4.0,
    };
    Some(BondBand { nominal, tolerance })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_placement_is_tried_by_the_work_of_the_first_not_the_clock() {
        // The 3 m cap's flagged first placement: tried at the default limit.
        assert!(second_placement_fits(1598, 38, 10.0));
        // The 20 m cap's: not at the default limit, but when the designer gives the fit a
        // minute.
        assert!(!second_placement_fits(17_311, 86, 10.0));
        assert!(second_placement_fits(17_311, 86, 60.0));
    }
}
