//! Optional shape-up (paper section 3.1, figure 3 right; Bouaziz, Deuss, Schwartzburg, Weise,
//! Pauly, "Shape-Up: shaping discrete geometry with projections", SGP 2012).
//!
//! Local step: every quad is replaced by the best-fitting square of side `t` (Kabsch rigid
//! fit of a reference square). Global step: every vertex moves to the mean of its corners'
//! targets. Unlike the paper's libigl run, every vertex is then projected back onto the input
//! surface (boundary vertices onto the input boundary, corners stay put), so the shell's
//! shape never changes; faces that still leave it are pulled back as in the fitting, and
//! the move is cut back (halved, up to four times, then undone) until edge midpoints and
//! centroids keep within the tolerance too.

use nalgebra::{Matrix3, Vector3};

use super::RemeshError;
use super::anchors::Anchors;
use super::budget::{Budget, Stop};
use super::cleanup::Quads;
use super::fit;
use super::surface::Locator;

/// Shares of the shape-up move tried, each half the one before.
const SHARE_HALVINGS: i32 = 4;

/// Runs `iterations` local-global rounds on `quads` and keeps the largest share of the move
/// that leaves the surface (at vertices, edge midpoints or centroids) by no more than
/// `tolerance * t`, or than the input did; the input unchanged if none does. When the time limit passes
/// the rounds done so far stand; a cancel is an error.
pub(crate) fn shapeup(
    quads: &Quads,
    locator: &Locator,
    t: f64,
    iterations: usize,
    tolerance: f64,
    budget: &mut Budget,
) -> Result<Quads, RemeshError> {
    let mut pos: Vec<Vector3<f64>> = quads.positions.iter().map(|p| p.coords).collect();
    let faces = &quads.faces;
    let anchors = Anchors::new(&mut pos, faces, locator, t);
    let h = t * 0.5;
    let square = [
        Vector3::new(-h, -h, 0.0),
        Vector3::new(h, -h, 0.0),
        Vector3::new(h, h, 0.0),
        Vector3::new(-h, h, 0.0),
    ];
    for round in 0..iterations {
        if !budget.poll(round as f64 / iterations.max(1) as f64) {
            if budget.stopped() == Some(Stop::Cancelled) {
                budget.check()?;
            }
            break;
        }
        let mut sum = vec![Vector3::zeros(); pos.len()];
        let mut count = vec![0.0; pos.len()];
        for f in faces.iter().filter(|f| f.len() == 4) {
            let p: Vec<Vector3<f64>> = f.iter().map(|&v| pos[v]).collect();
            let c = p.iter().sum::<Vector3<f64>>() / 4.0;
            let mut cov = Matrix3::zeros();
            for k in 0..4 {
                cov += (p[k] - c) * square[k].transpose();
            }
            let svd = cov.svd(true, true);
            let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
                continue;
            };
            let mut d = Matrix3::identity();
            if (u * vt).determinant() < 0.0 {
                d[(2, 2)] = -1.0;
            }
            let r = u * d * vt;
            for k in 0..4 {
                sum[f[k]] += c + r * square[k];
                count[f[k]] += 1.0;
            }
        }
        for v in 0..pos.len() {
            if anchors.pinned[v] || count[v] == 0.0 {
                continue;
            }
            pos[v] = anchors.project(locator, v, &(sum[v] / count[v]));
        }
    }
    // Vertices are on the surface; edges and faces between them may have left it. The
    // largest share of the shape-up move (all, half, a quarter, ...) whose faces, pulled back
    // as the fitting does, keep within the tolerance (or within the input's own deviation)
    // is kept.
    let worst = |pos: &[Vector3<f64>]| {
        faces
            .iter()
            .map(|f| fit::deviation(pos, f, locator))
            .fold(0.0, f64::max)
    };
    let before: Vec<Vector3<f64>> = quads.positions.iter().map(|p| p.coords).collect();
    let allowed = (tolerance * t).max(worst(&before));
    for halvings in 0..SHARE_HALVINGS {
        let share = 0.5f64.powi(halvings);
        let mut trial: Vec<Vector3<f64>> = (0..pos.len())
            .map(|v| {
                if anchors.pinned[v] {
                    before[v]
                } else {
                    anchors.project(locator, v, &(before[v] + (pos[v] - before[v]) * share))
                }
            })
            .collect();
        fit::conform(&mut trial, faces, &anchors, locator, t);
        fit::shorten_boundary_chords(&mut trial, faces, &anchors, locator, tolerance * t);
        if worst(&trial) <= allowed {
            return Ok(Quads {
                positions: trial.iter().map(|&p| p.into()).collect(),
                faces: faces.clone(),
            });
        }
    }
    Ok(quads.clone())
}
