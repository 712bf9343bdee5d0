//! Step 5 of the [cleanup](super), first part: the repaired quads onto the input. Rows are
//! extended over gaps to the input boundary ([`fit`]), boundary vertices snapped onto it
//! (input corners onto corners) and all others onto the surface with a few rounds of
//! smoothing; boundary faces that still leave the surface are peeled off and the gap closed
//! by a fresh extension, a few times.

use nalgebra::Vector3;

use super::manifold::drop_small_components;
use super::valence::remove_doublets;
use crate::remesh::RemeshError;
use crate::remesh::anchors::Anchors;
use crate::remesh::budget::{Budget, Stop};
use crate::remesh::fit;
use crate::remesh::quadmesh::{boundary_loops, compact};
use crate::remesh::surface::Locator;

/// Puts the repaired quads onto the input (see the module documentation): the vertices of
/// `pos` onto the surface, rows extended to the input boundary, the boundary snapped and
/// relaxed; then up to [`FIT_ROUNDS`] + 1 rounds of pulling faces back onto the surface and
/// peeling the boundary faces that still leave it. When the time limit passes the mesh as it
/// stands is kept; a cancel is an error.
pub(super) fn snap_and_peel(
    pos: &mut Vec<Vector3<f64>>,
    faces: &mut Vec<Vec<usize>>,
    locator: &Locator,
    t: f64,
    budget: &mut Budget,
) -> Result<(), RemeshError> {
    for p in pos.iter_mut() {
        *p = locator.closest(p).0;
    }
    let loops = boundary_loops(faces);
    fit::extend_boundary(pos, faces, &loops, locator, t);
    relax(pos, faces, locator, t, 6);
    for round in 0..=FIT_ROUNDS {
        if !budget.poll(0.5 + 0.5 * round as f64 / (FIT_ROUNDS + 1) as f64) {
            match budget.stopped() {
                Some(Stop::Cancelled) => budget.check()?,
                _ => break,
            }
        }
        let anchors = Anchors::new(pos, faces, locator, t);
        fit::conform(pos, faces, &anchors, locator, t);
        // Faces at the boundary that still leave the surface are peeled off and the gap is
        // closed again by a fresh row extension; in the last round the new boundary vertices
        // are only put onto the input boundary, and the peeling is kept only if it helped.
        let bad: Vec<bool> = crate::parallel::map(faces.len(), |fi| {
            let f = &faces[fi];
            f.iter().any(|&v| !anchors.bnbrs[v].is_empty())
                && fit::deviation(pos, f, locator) > PEEL * t
        });
        if !bad.iter().any(|&b| b) {
            break;
        }
        let before = (round == FIT_ROUNDS).then(|| (pos.clone(), faces.clone()));
        let mut kept: Vec<Vec<usize>> = faces
            .iter()
            .zip(&bad)
            .filter(|(_, b)| !**b)
            .map(|(f, _)| f.clone())
            .collect();
        drop_small_components(&mut kept);
        remove_doublets(&mut kept);
        let (p2, f2) = compact(std::mem::take(pos), kept);
        *pos = p2;
        *faces = f2;
        if let Some((old_pos, old_faces)) = before {
            let anchors = Anchors::new(pos, faces, locator, t);
            for (v, p) in pos.iter_mut().enumerate() {
                if !anchors.bnbrs[v].is_empty() && !anchors.pinned[v] {
                    *p = anchors.project(locator, v, p);
                }
            }
            fit::conform(pos, faces, &anchors, locator, t);
            let worst = |pos: &[Vector3<f64>], faces: &[Vec<usize>]| {
                faces
                    .iter()
                    .map(|f| fit::deviation(pos, f, locator))
                    .fold(0.0, f64::max)
            };
            let on_boundary = (0..pos.len()).all(|v| {
                anchors.bnbrs[v].is_empty()
                    || locator
                        .closest_boundary(&pos[v])
                        .is_some_and(|q| (q - pos[v]).norm() <= 0.04 * t)
            });
            if !on_boundary || worst(pos, faces) >= worst(&old_pos, &old_faces) {
                *pos = old_pos;
                *faces = old_faces;
            }
        } else {
            let loops = boundary_loops(faces);
            fit::extend_boundary(pos, faces, &loops, locator, t);
            relax(pos, faces, locator, t, 2);
        }
    }
    Ok(())
}
/// Rounds of peeling and re-extending boundary faces that leave the surface.
const FIT_ROUNDS: usize = 4;

/// Deviation from the surface (times `t`) at which a boundary face is peeled off.
const PEEL: f64 = 0.08;

/// Snaps boundary vertices onto the input boundary (input corners onto corners), the rest
/// onto the surface, with `rounds` of damped Laplacian smoothing in between.
fn relax(pos: &mut [Vector3<f64>], faces: &[Vec<usize>], locator: &Locator, t: f64, rounds: usize) {
    let n = pos.len();
    let anchors = Anchors::new(pos, faces, locator, t);
    // Every vertex moves on its own (from the positions before the round), so each round's
    // moves run on the threads of `parallel` and give the same positions however split.
    let projected = crate::parallel::map(n, |v| {
        if anchors.pinned[v] {
            pos[v]
        } else {
            anchors.project(locator, v, &pos[v])
        }
    });
    pos.copy_from_slice(&projected);
    for _ in 0..rounds {
        let old = &*pos;
        let moved = crate::parallel::map(n, |v| {
            if anchors.pinned[v] {
                return old[v];
            }
            let list = if anchors.bnbrs[v].is_empty() {
                &anchors.nbrs[v]
            } else {
                &anchors.bnbrs[v]
            };
            if list.is_empty() {
                return old[v];
            }
            let mean =
                list.iter().fold(Vector3::zeros(), |acc, &w| acc + old[w]) / list.len() as f64;
            anchors.project(locator, v, &(old[v] * 0.5 + mean * 0.5))
        });
        pos.copy_from_slice(&moved);
    }
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use super::*;
    use crate::control::Control;
    use crate::remesh::quadmesh::samples::{grid, lines};
    use crate::remesh::surface::samples::sheet;

    /// Locator of a flat 2 x 2 input at the boundary scale of `t`.
    fn flat(t: f64) -> Locator {
        let mut input = sheet(8, 0.25, (0..0, 0..0), |_, _| 0.0);
        input.set_boundary_scale(t / 2.0);
        Locator::new(&input)
    }

    /// Whether vertex `v` is on a boundary edge of `faces`.
    fn rim(faces: &[Vec<usize>], v: usize) -> bool {
        boundary_loops(faces).iter().any(|lp| lp.contains(&v))
    }

    #[test]
    fn relaxing_puts_the_rim_on_the_input_boundary_and_the_rest_on_the_surface() {
        let locator = flat(0.5);
        let (mut pos, faces) = grid(&lines(0.1, 1.9, 4), &lines(0.1, 1.9, 4));
        for (k, p) in pos.iter_mut().enumerate() {
            p.z = 0.05 * ((k * 7) % 5) as f64 - 0.1;
        }
        relax(&mut pos, &faces, &locator, 0.5, 6);
        for (v, p) in pos.iter().enumerate() {
            assert!(p.z.abs() < 1e-12, "on the surface");
            let on_outline = p.x.abs() < 1e-12
                || p.y.abs() < 1e-12
                || (p.x - 2.0).abs() < 1e-12
                || (p.y - 2.0).abs() < 1e-12;
            assert_eq!(on_outline, rim(&faces, v), "vertex {v} at {p:?}");
        }
        for c in [0, 4, 20, 24] {
            assert!(
                [0.0, 2.0].contains(&pos[c].x) && [0.0, 2.0].contains(&pos[c].y),
                "corner {c} on an input corner"
            );
        }
    }

    #[test]
    fn quads_short_of_the_boundary_are_extended_onto_it() {
        // Quads of t = 0.25 cover [0, 2] x [0, 1.5] of the 2 x 2 input: two rows short of its
        // far edge.
        let t = 0.25;
        let locator = flat(t);
        let (mut pos, mut faces) = grid(&lines(0.0, 2.0, 8), &lines(0.0, 1.5, 6));
        let short = faces.len();
        let mut control = Control::none();
        let mut budget = Budget::new(&mut control, Instant::now(), Duration::from_secs(60));
        snap_and_peel(&mut pos, &mut faces, &locator, t, &mut budget).unwrap();
        assert!(faces.len() > short && faces.iter().all(|f| f.len() == 4));
        for (v, p) in pos.iter().enumerate().filter(|&(v, _)| rim(&faces, v)) {
            let q = locator.closest_boundary(p).unwrap();
            assert!(
                (q - p).norm() < 0.05 * t,
                "rim vertex {v} at {p:?} is off the input boundary"
            );
        }
        let covered: f64 = faces
            .iter()
            .map(|f| (pos[f[2]] - pos[f[0]]).cross(&(pos[f[3]] - pos[f[1]])).z / 2.0)
            .sum();
        assert!((covered - 4.0).abs() < 1e-9, "covered {covered}");
    }
}
