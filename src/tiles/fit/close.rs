//! Closing tears too narrow for a piece: the head joints of a course take up a gap a mason
//! would not cut a piece for.
//!
//! The placement gathers what a course's joints cannot close into tears ([`super::solve`]'s
//! capped joint cost), and a tear about a half tile long takes a standard piece
//! ([`super::rooms`]). A tear between the two ([`super::tear_gap`] up to the shortest room)
//! would take a piece cut to it, a few centimetres long: the cut the fit exists to avoid.
//! Where the course around it has slack, a mason closes it instead, pressing the head joints
//! along the course a few millimetres each. This step does the same: the tear's joint is
//! made to cost as a joint again, however wide (not capped), and the tiles are placed again
//! from where they are, so that its neighbours slide to close it; kept only when the joints
//! the tiles cannot keep become fewer and their p95 deviation from the joint no higher, as a
//! round of rooms is kept.

use nalgebra::Vector3;

use super::closers;
use super::rooms::{Placement, ROUND_STEPS, Setting, shortest_room};
use super::solve::Problem;
use super::tear_gap;

/// What [`close`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Closed {
    /// Steps of the placement done again.
    pub iterations: usize,
    /// Whether `keep_going` stopped it (the placement before it is kept).
    pub stopped: bool,
    /// Tears closed to a joint (at most [`tear_gap`] wide) by the placement kept; 0 when it
    /// was not kept.
    pub tears: usize,
    /// The least-squares objective (with every joint capped as in the other placements) of
    /// the placement kept, if it was.
    pub end: Option<f64>,
}

/// Places the tiles of `placement` again with the head joints torn wider than [`tear_gap`]
/// but too narrow for a room's half tile ([`shortest_room`]) pulled shut, once, within
/// `budget` tile steps of `work` (updated); the new placement is kept when its joints fit
/// better ([`closers::fits_better`]). Tiles in `skip` (closers, to be cut) close nothing.
///
/// The placement starts from the frames put back on the surface as a step puts them
/// ([`Problem::moved`]): near a fold or a corner of the surface's edge that can move a tile
/// (43 mm on the shared tubemesh), and a start that no step can reach would make every
/// step look worse than it, so that none is taken.
pub(crate) fn close(
    placement: &mut Placement,
    skip: &[usize],
    setting: &Setting<'_>,
    (work, budget): (&mut usize, usize),
    keep_going: &mut dyn FnMut(f64) -> bool,
) -> Closed {
    let &Setting { spec, options, .. } = setting;
    let mut closed = Closed {
        iterations: 0,
        stopped: false,
        tears: 0,
        end: None,
    };
    let steps = ROUND_STEPS.min(options.max_iterations);
    if *work + placement.tiles.len() * steps > budget {
        return closed;
    }
    let gaps = closers::gaps(&placement.tiles, &placement.frames, &placement.contacts);
    let shortest_room = shortest_room(spec);
    let skipped = |t: usize| skip.binary_search(&t).is_ok();
    let closing: Vec<bool> = placement
        .contacts
        .iter()
        .zip(&gaps)
        .map(|(c, &gap)| {
            !c.sides[0].is_long()
                && !c.sides[1].is_long()
                && !c.tiles.iter().any(|&t| skipped(t))
                && gap > tear_gap(spec)
                && gap < shortest_room
        })
        .collect();
    if !closing.contains(&true) {
        return closed;
    }
    let bands = placement.bands(spec, options);
    let problem = placement.problem(&bands, setting, &closing);
    let mut frames: Vec<_> = placement
        .frames
        .iter()
        .map(|f| problem.moved(f, &Vector3::zeros()).0)
        .collect();
    let progress = problem.solve(&mut frames, steps, keep_going);
    closed.iterations = progress.iterations;
    closed.stopped = progress.stopped;
    *work += placement.tiles.len() * progress.iterations;
    let after = closers::gaps(&placement.tiles, &frames, &placement.contacts);
    let tear = tear_gap(spec);
    if !progress.stopped
        && closers::fits_better(&gaps, &after, spec.joint, options.overlap_tolerance, tear)
    {
        closed.tears = closing
            .iter()
            .zip(&after)
            .filter(|&(&c, &g)| c && g <= tear)
            .count();
        closed.end = Some(
            Problem {
                closing: &[],
                ..problem
            }
            .objective(&frames),
        );
        placement.frames = frames;
    }
    closed
}

#[cfg(test)]
mod tests {
    use super::super::FitOptions;
    use super::super::rooms::tests::{SPEC, course};
    use super::super::weights_for;
    use super::*;
    use crate::geom::SurfaceIndex;

    fn closed(placement: &mut Placement, surface: &SurfaceIndex) -> Closed {
        let options = FitOptions::for_spec(&SPEC);
        let setting = Setting {
            spec: &SPEC,
            options: &options,
            weights: weights_for(&SPEC),
            surface,
        };
        close(placement, &[], &setting, (&mut 0, usize::MAX), &mut |_| {
            true
        })
    }

    #[test]
    fn a_tear_too_narrow_for_a_half_closes_where_the_course_can_slide() {
        // 70 mm between the third tile and the fourth, the three last free to slide back
        // along a surface longer than the course.
        let (mut placement, surface) = course(0.06, 0.0);
        let result = closed(&mut placement, &surface);
        assert!(!result.stopped);
        assert_eq!(result.tears, 1);
        assert!(result.end.is_some());
        assert_eq!(placement.tiles.len(), 6);
        let gaps = closers::gaps(&placement.tiles, &placement.frames, &placement.contacts);
        for (c, g) in placement.contacts.iter().zip(&gaps) {
            assert!((g - SPEC.joint).abs() < 1e-3, "{c:?}: {g}");
        }
    }

    #[test]
    fn a_wide_joint_or_a_room_is_not_closed() {
        // 20 mm: a joint a little wide, no tear. 180 mm: a room for a half ([`super::rooms`]).
        for shift in [0.01, 0.17] {
            let (mut placement, surface) = course(shift, 0.0);
            let frames = placement.frames.clone();
            let result = closed(&mut placement, &surface);
            assert_eq!(result.iterations, 0, "shift {shift}");
            assert_eq!((result.tears, result.end), (0, None), "shift {shift}");
            assert_eq!(placement.frames, frames);
        }
    }
}
