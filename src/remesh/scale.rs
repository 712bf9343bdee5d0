//! The scale field: a smooth log-scale `phi` per vertex by which the lattice spacing may
//! vary, `t exp(phi)`, so that rows narrow and widen gently where the surface and the
//! crosses' turning ask for it instead of ending in dislocations (pairs of irregular
//! vertices). The position field integrates a first lattice at this scale and keeps it
//! where it leaves clearly fewer dislocations, then always solves at one spacing
//! ([`super::position`]'s `integrate` says why).
//!
//! A lattice of one spacing closes around a triangle only if the edge vectors, read in the
//! crosses' frames, sum to zero ([`super::position`]'s Burgers density). On a developable
//! surface with parallel crosses they do; on a sphere, whose crosses turn by its Gaussian
//! curvature, they do not, and the fixed-spacing lattice must end rows (the paper's Figure 3
//! singular quads; issue 19's domes). Scaling every edge vector by `exp(-phi)` and asking the
//! sums to vanish gives, to first order, `grad phi` equal to the density rotated by a
//! quarter turn and divided by the area: a Poisson problem for `phi`, the discrete form of
//! the conformal scale of integer-grid maps with a scale (Myles and Zorin, "Controlled-
//! distortion constrained global parametrization", SIGGRAPH 2013; Ben-Chen, Gotsman and
//! Bunin, "Conformal flattening by curvature prescription and metric scaling", 2008, where
//! the log-scale solves a Poisson equation with the Gaussian curvature). Triangles where the
//! crosses turn by a quarter (the field's cones) are left out: there the lattice turns, it
//! does not scale.
//!
//! Quads must stay near the half tile's size, so the solved scale is clamped to the caller's
//! limit: where the surface asks for more (near the field's cones the log-scale grows like
//! the logarithm of the distance; a large dome's rows shrink by more than the limit from rim
//! to crown) the rest is left to dislocations, as without a scale. Clamping was measured
//! against shrinking the whole field until 98 % of it fits the limit: shrunk, a shell whose
//! scale peaks somewhere keeps too little of it everywhere else (README, *Remesher*). Small
//! scales are dropped ([`DEAD_ZONE`]).

use nalgebra::{Matrix2, Vector2};

use super::flow::{self, Jumps};
use super::linalg::conjugate_gradient;
use super::surface::Surface;
use crate::parallel::Scatter;

/// Conjugate-gradient steps of the Poisson solve.
const ITERATIONS: usize = 400;

/// Largest change of the log-scale per quad length a triangle may ask for (see [`solve`]).
const MAX_GRADIENT: f64 = 0.5;

/// Log-scales within this of zero are dropped (and the rest moved towards zero by it): on a
/// developable surface the solve returns a few thousandths from the discretisation alone,
/// and on a gently curved sail a few hundredths that the lattice of one spacing absorbs
/// anyway; scaled there, the first lattice's rows meet the boundary a row apart from where
/// the later rounds pin them, and end one row inside it (the sail of README, *Remesher*,
/// integrated at the scale: 13 irregular vertices at 0.01, 2 at 0.03, 1 without a scale).
const DEAD_ZONE: f64 = 0.03;

/// Step from `x` to `y` (an edge of `s`) in `x`'s frame, from the per-edge vectors `delta`
/// (in the frame of the edge's lower end) and `transfer` (the higher end's frame into the
/// lower's).
pub(crate) fn step(
    s: &Surface,
    delta: &[Vector2<f64>],
    transfer: &[Matrix2<f64>],
    x: usize,
    y: usize,
) -> Vector2<f64> {
    let e = s.edge(x, y);
    if x < y {
        delta[e]
    } else {
        -(transfer[e].transpose() * delta[e])
    }
}

/// Step from `x` to `y` in the frame halfway between theirs: `x`'s frame turned by half of
/// what the crosses turn along the edge beyond whole quarter turns. Read in its start's frame,
/// a step misses half of that turn, and around a triangle the misses add up to as much as
/// the misclosure sought, and in another direction (crosses along the radii of a flat ring:
/// the start frames give a misclosure along the radii, twice as long as the true one, which
/// lies along the rings); read halfway, each edge gives the two triangles beside it the
/// same step, so a patch's misclosure is the sum of its boundary steps.
fn mid_step(
    s: &Surface,
    delta: &[Vector2<f64>],
    transfer: &[Matrix2<f64>],
    x: usize,
    y: usize,
) -> Vector2<f64> {
    let angle = flow::turn_angle(&transfer[s.edge(x, y)]);
    let quarter = std::f64::consts::FRAC_PI_2;
    let rest = angle - quarter * (angle / quarter).round();
    // `x`'s frame turns towards `y`'s by `rest` when `x` is the lower end, by `-rest` when
    // it is the higher; components in a frame turned by `a` are the vector turned by `-a`.
    let half = if x < y { -rest / 2.0 } else { rest / 2.0 };
    nalgebra::Rotation2::new(half) * step(s, delta, transfer, x, y)
}

/// Carries vectors in `y`'s frame into `x`'s by the whole quarter turns between the frames,
/// as the integer steps are carried.
fn carry(s: &Surface, transfer: &[Matrix2<f64>], x: usize, y: usize) -> Matrix2<f64> {
    let r = flow::quarter_turn_matrix(&transfer[s.edge(x, y)]);
    if x < y { r } else { r.transpose() }
}

/// The three steps around triangle `[a, b, c]` carried into `a`'s frame by whole quarter
/// turns, `a -> b`, `b -> c`, `c -> a`: their sum is the lattice's misclosure there (the
/// Burgers density of [`super::position`]), which the quarter turns alone make meaningless
/// around a cone of the field.
pub(crate) fn steps_around(
    s: &Surface,
    delta: &[Vector2<f64>],
    transfer: &[Matrix2<f64>],
    [a, b, c]: [usize; 3],
) -> [Vector2<f64>; 3] {
    [
        mid_step(s, delta, transfer, a, b),
        carry(s, transfer, a, b) * mid_step(s, delta, transfer, b, c),
        carry(s, transfer, a, c) * mid_step(s, delta, transfer, c, a),
    ]
}

/// Solves the log-scale per vertex of `s` for the edge vectors `delta` and frame transfers
/// `transfer` (see [`super::position`]), leaving out the triangles `cones` says are cones of
/// the field, limited to `[-limit, limit]` as described in the
/// module's documentation. A `limit` of zero gives zero everywhere.
pub(crate) fn solve(
    s: &Surface,
    delta: &[Vector2<f64>],
    transfer: &[Matrix2<f64>],
    cones: &Jumps,
    t: f64,
    limit: f64,
    keep_going: &mut dyn FnMut(usize) -> bool,
) -> Vec<f64> {
    let n = s.len();
    if limit <= 0.0 || n == 0 {
        return vec![0.0; n];
    }
    // Per non-cone triangle: its vertices, the coefficient vector of each vertex's log-scale
    // in the linearised closure, its closure at zero scale, and its weight.
    struct Row {
        v: [usize; 3],
        coef: [Vector2<f64>; 3],
        closure: Vector2<f64>,
        weight: f64,
    }
    let area = s.vertex_areas();
    let rows: Vec<Row> = s
        .tris
        .iter()
        .enumerate()
        .filter_map(|(ti, &tri)| {
            let [a, b, c] = tri;
            let twice = (s.pos[b] - s.pos[a]).cross(&(s.pos[c] - s.pos[a])).norm();
            if twice <= 1e-300 {
                return None;
            }
            if cones.is_cone(ti) {
                return None;
            }
            let [ab, bc, ca] = steps_around(s, delta, transfer, tri);
            // exp(-phi) on an edge is linearised as 1 - (phi_x + phi_y) / 2, about the
            // triangle's steps closed by spreading their sum evenly: then the coefficients
            // sum to zero and a constant scale, which closes nothing, changes nothing (with
            // the raw steps, phi = 1 everywhere would zero every linearised closure).
            let closure = ab + bc + ca;
            // A closure asking the scale to change by more than half per quad length is not
            // the surface's (a sliver, a fold, a crumpled corner): it is left out.
            if closure.norm() > MAX_GRADIENT * twice / 2.0 / t {
                return None;
            }
            let [ab, bc, ca] = [ab, bc, ca].map(|x| x - closure / 3.0);
            Some(Row {
                v: tri,
                coef: [(ab + ca) / 2.0, (ab + bc) / 2.0, (bc + ca) / 2.0],
                closure,
                // Each row is about the triangle's area times a gradient: dividing its square
                // by the area gives the gradient's squared norm integrated over the triangle.
                weight: 2.0 / twice,
            })
        })
        .collect();
    let total_area: f64 = area.iter().sum();
    if rows.is_empty() || total_area <= 0.0 {
        return vec![0.0; n];
    }
    // A tiny pull to zero (relative to the smallest stiffness a vertex has, about one) fixes
    // the free constant.
    let pull: Vec<f64> = area
        .iter()
        .map(|a| 1e-6 * a / total_area * n as f64)
        .collect();
    let scatter = Scatter::default();
    let apply = |x: &[f64], out: &mut [f64]| {
        for (o, (x, p)) in out.iter_mut().zip(x.iter().zip(&pull)) {
            *o = p * x;
        }
        scatter.add(rows.len(), out, |range, out| {
            for row in &rows[range] {
                let r: Vector2<f64> = (0..3).map(|k| row.coef[k] * x[row.v[k]]).sum();
                for k in 0..3 {
                    out[row.v[k]] += row.weight * row.coef[k].dot(&r);
                }
            }
        });
    };
    let mut rhs = vec![0.0; n];
    for row in &rows {
        for k in 0..3 {
            rhs[row.v[k]] += row.weight * row.coef[k].dot(&row.closure);
        }
    }
    let mut phi = vec![0.0; n];
    conjugate_gradient(apply, &rhs, &mut phi, ITERATIONS, 1e-8, None, keep_going);
    limit_scale(&mut phi, &area, limit);
    phi
}

/// Centres `phi` on its area-weighted mean (quads of `t` on average), moves it towards zero by
/// [`DEAD_ZONE`] and clamps it to `[-limit, limit]`.
fn limit_scale(phi: &mut [f64], area: &[f64], limit: f64) {
    let total: f64 = area.iter().sum();
    let mean = phi.iter().zip(area).map(|(p, a)| p * a).sum::<f64>() / total;
    for p in phi.iter_mut() {
        let centred = *p - mean;
        *p = (centred.signum() * (centred.abs() - DEAD_ZONE).max(0.0)).clamp(-limit, limit);
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Vector3;

    use super::*;
    use crate::remesh::position::{bases, edge_frames};
    use crate::remesh::surface::samples::sheet;

    /// The scale of `s` for quads of 0.1, limited to `limit`, solved to the end.
    fn scale_of(
        s: &Surface,
        delta: &[Vector2<f64>],
        transfer: &[Matrix2<f64>],
        limit: f64,
    ) -> Vec<f64> {
        let cones = Jumps::new(s, transfer);
        solve(s, delta, transfer, &cones, 0.1, limit, &mut |_| true)
    }

    /// Sum of |closure| over the non-cone triangles with edge vectors scaled by `phi`.
    fn misclosure(
        s: &Surface,
        delta: &[Vector2<f64>],
        transfer: &[Matrix2<f64>],
        phi: &[f64],
    ) -> f64 {
        let scaled: Vec<Vector2<f64>> = s
            .edges
            .iter()
            .zip(delta)
            .map(|(&[a, b], d)| d * (-(phi[a] + phi[b]) / 2.0).exp())
            .collect();
        let cones = Jumps::new(s, transfer);
        s.tris
            .iter()
            .enumerate()
            .filter(|&(ti, _)| !cones.is_cone(ti))
            .map(|(_, &tri)| {
                let [x, y, z] = steps_around(s, &scaled, transfer, tri);
                (x + y + z).norm()
            })
            .sum()
    }

    #[test]
    fn parallel_crosses_on_a_plane_need_no_scale() {
        let s = sheet(12, 0.1, (0..0, 0..0), |_, _| 0.0);
        let frames = vec![Vector3::x(); s.len()];
        let (transfer, delta) = edge_frames(&s, &bases(&s, &frames));
        let phi = scale_of(&s, &delta, &transfer, 0.2);
        assert!(phi.iter().all(|p| p.abs() < 1e-9), "{phi:?}");
    }

    #[test]
    fn crosses_turning_on_a_plane_are_closed_by_a_scale_within_the_limit() {
        // Crosses turning by 0.2 rad per metre along x: a polar-like lattice whose rows must
        // spread or narrow across y, by a log-scale of 0.2 y (+-0.2 over the 2 m patch). The
        // scale takes most of the misclosure away; the dead zone (0.03) keeps the rest.
        let s = sheet(20, 0.1, (0..0, 0..0), |_, _| 0.0);
        let frames: Vec<Vector3<f64>> = s
            .pos
            .iter()
            .map(|p| Vector3::new((0.2 * p.x).cos(), (0.2 * p.x).sin(), 0.0))
            .collect();
        let (transfer, delta) = edge_frames(&s, &bases(&s, &frames));
        let phi = scale_of(&s, &delta, &transfer, 0.5);
        let before = misclosure(&s, &delta, &transfer, &vec![0.0; s.len()]);
        let after = misclosure(&s, &delta, &transfer, &phi);
        // (The dead zone leaves a thin band around phi = 0 unscaled.)
        assert!(after < 0.2 * before, "{before} -> {after}");
        // Limited, the same field keeps every vertex within the limit.
        let limited = scale_of(&s, &delta, &transfer, 0.01);
        assert!(limited.iter().all(|p| p.abs() <= 0.01 + 1e-12));
        assert!(limited.iter().any(|p| p.abs() > 0.005));
    }
}
