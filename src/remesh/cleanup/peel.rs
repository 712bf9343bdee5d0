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
pub(super) fn snap_and_peel(pos: &mut Vec<Vector3<f64>>, faces: &mut Vec<Vec<usize>>, locator: &Locator, t: f64, budget: &mut Budget) -> Result<(), RemeshError> {
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
        let bad: Vec<bool> = faces
            .iter()
            .map(|f| f.iter().any(|&v| !anchors.bnbrs[v].is_empty()) && fit::deviation(pos, f, locator) > PEEL * t)
            .collect();
        if !bad.iter().any(|&b| b) {
            break;
        }
        let before = (round == FIT_ROUNDS).then(|| (pos.clone(), faces.clone()));
        let mut kept: Vec<Vec<usize>> = faces.iter().zip(&bad).filter(|(_, b)| !**b).map(|(f, _)| f.clone()).collect();
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
            let worst = |pos: &[Vector3<f64>], faces: &[Vec<usize>]| faces.iter().map(|f| fit::deviation(pos, f, locator)).fold(0.0, f64::max);
            let on_boundary = (0..pos.len()).all(|v| {
                anchors.bnbrs[v].is_empty() || locator.closest_boundary(&pos[v]).is_some_and(|q| (q - pos[v]).norm() <= 0.04 * t)
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
    for (v, p) in pos.iter_mut().enumerate() {
        if !anchors.pinned[v] {
            *p = anchors.project(locator, v, p);
        }
    }
    for _ in 0..rounds {
        let old = pos.to_vec();
        for v in 0..n {
            if anchors.pinned[v] {
                continue;
            }
            let list = if anchors.bnbrs[v].is_empty() { &anchors.nbrs[v] } else { &anchors.bnbrs[v] };
            if list.is_empty() {
                continue;
            }
            let mean = list.iter().fold(Vector3::zeros(), |acc, &w| acc + old[w]) / list.len() as f64;
            pos[v] = anchors.project(locator, v, &(old[v] * 0.5 + mean * 0.5));
        }
    }
}
