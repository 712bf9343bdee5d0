//! The 4-RoSy orientation field (Instant Meshes section 4; the paper's step 1).
//!
//! A cross at vertex `i` is stored as one complex number `z_i = e^{4 i theta_i}` in a local
//! tangent frame, so the four directions of a cross are one value (Knöppel, Crane, Pinkall,
//! Schröder, "Globally optimal direction fields", SIGGRAPH 2013; Ray et al. 2008). The
//! smoothest field is then the minimiser of a Hermitian quadratic energy
//!
//! `sum_edges |z_a - r_ab z_b|^2 + sum_i w_i |z_i - c_i|^2`
//!
//! where `r_ab` is the discrete Levi-Civita transport (to the fourth power), `c_i` the
//! principal curvature direction (to the fourth power) and `w_i` how anisotropic the surface
//! is there ([`alignment_weight`]: zero where the two principal curvatures are nearly equal,
//! on a sphere, a dome's crown or a plane, where the principal directions are noise; the
//! same at any model scale), and the boundary crosses are fixed to the boundary tangents (Dirichlet), so quads
//! line up with the boundary. One global conjugate-gradient solve replaces Instant Meshes'
//! multi-resolution Gauss-Seidel sweeps and is deterministic.

use nalgebra::{Matrix5, Vector3, Vector5};

use super::budget::Budget;
use super::linalg::conjugate_gradient;
use super::surface::{Surface, any_tangent};
use super::{FieldDirection, RemeshOptions};

/// Complex number as (re, im); the field needs only a few operations.
#[derive(Debug, Clone, Copy, PartialEq)]
struct C(f64, f64);

impl C {
    fn from_angle(a: f64) -> Self {
        C(a.cos(), a.sin())
    }
    fn mul(self, o: C) -> C {
        C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    fn conj(self) -> C {
        C(self.0, -self.1)
    }
    fn scale(self, s: f64) -> C {
        C(self.0 * s, self.1 * s)
    }
    fn add(self, o: C) -> C {
        C(self.0 + o.0, self.1 + o.1)
    }
    fn norm(self) -> f64 {
        self.0.hypot(self.1)
    }
}

/// Per-vertex tangent frames `(e, n x e)` the complex numbers refer to.
fn reference_frames(s: &Surface) -> Vec<Vector3<f64>> {
    (0..s.len())
        .map(|v| {
            let n = s.normals[v];
            s.adj[v]
                .first()
                .and_then(|&(w, _)| {
                    let d = s.edge_vec(v, w);
                    (d - n * n.dot(&d)).try_normalize(1e-300)
                })
                .unwrap_or_else(|| any_tangent(&n))
        })
        .collect()
}

/// Angle of a 3D vector in the tangent frame `(e, n x e)`.
fn angle_in(e: &Vector3<f64>, n: &Vector3<f64>, d: &Vector3<f64>) -> f64 {
    let b = n.cross(e);
    d.dot(&b).atan2(d.dot(e))
}

/// The representative of the cross `o_b` (4 rotations about `n_b`) closest to `o_a`.
pub(crate) fn match_rosy(
    o_a: &Vector3<f64>,
    o_b: &Vector3<f64>,
    n_b: &Vector3<f64>,
) -> Vector3<f64> {
    let t = n_b.cross(o_b);
    let candidates = [*o_b, t, -o_b, -t];
    let mut best = candidates[0];
    let mut best_dot = f64::NEG_INFINITY;
    for c in candidates {
        let d = c.dot(o_a);
        if d > best_dot {
            best_dot = d;
            best = c;
        }
    }
    best
}

/// Principal curvature direction (angle in the vertex frame) and anisotropy `|k1 - k2|`,
/// from a least-squares quadric `h = A x^2 + B xy + C y^2 + D x + E y` over the 2-ring.
fn curvature(
    s: &Surface,
    frames: &[Vector3<f64>],
    v: usize,
    mark: &mut [usize],
) -> Option<(f64, f64, f64)> {
    let n = s.normals[v];
    let e = frames[v];
    let b = n.cross(&e);
    let mut ring: Vec<usize> = Vec::new();
    mark[v] = v;
    for &(w, _) in &s.adj[v] {
        if mark[w] != v {
            mark[w] = v;
            ring.push(w);
        }
    }
    let first = ring.len();
    for k in 0..first {
        for &(w, _) in &s.adj[ring[k]] {
            if mark[w] != v {
                mark[w] = v;
                ring.push(w);
            }
        }
    }
    if ring.len() < 5 {
        return None;
    }
    let mut m = Matrix5::zeros();
    let mut rhs = Vector5::zeros();
    for &w in &ring {
        let d = s.edge_vec(v, w);
        let (x, y, h) = (d.dot(&e), d.dot(&b), d.dot(&n));
        let row = Vector5::new(x * x, x * y, y * y, x, y);
        m += row * row.transpose();
        rhs += row * h;
    }
    let sol = m.lu().solve(&rhs)?;
    let (p, q, r) = (2.0 * sol[0], sol[1], 2.0 * sol[2]);
    let aniso = ((p - r) * (p - r) + 4.0 * q * q).sqrt();
    let mean = (p + r).abs() * 0.5;
    let angle = 0.5 * (2.0 * q).atan2(p - r);
    Some((angle, aniso, mean))
}

/// How much a vertex's cross is pulled towards its principal directions, in `[0, 1]`: the
/// relative anisotropy `a = |k1 - k2| / (|k1 - k2| + |H| + 4 / extent)` squared, but nothing
/// where `a` is below [`UMBILIC`] (a sphere, a plane, the crown of a dome: there the two
/// principal curvatures are equal and the principal directions are noise, so only the
/// boundary and smoothness orient the crosses), rising smoothly to the full `a^2` at twice
/// that. `extent` is the surface's size (its bounding-box diagonal), which keeps nearly flat
/// parts from reading as anisotropic. Every term is a curvature (1 / length), so the weight
/// does not change when the model is scaled: a 3 m and a 20 m dome are treated alike.
fn alignment_weight(aniso: f64, mean: f64, extent: f64) -> f64 {
    let rel = aniso / (aniso + mean + 4.0 / extent);
    if !rel.is_finite() {
        return 0.0;
    }
    let ramp = ((rel - UMBILIC) / UMBILIC).clamp(0.0, 1.0);
    rel * rel * ramp * ramp * (3.0 - 2.0 * ramp)
}

/// Relative anisotropy below which a point counts as umbilic (see [`alignment_weight`]).
const UMBILIC: f64 = 0.05;

/// Solves the orientation field on `s`; returns one unit tangent per vertex (any of the four
/// directions of its cross).
/// Stops early (with a usable but less smooth field) once `budget` says so.
pub(crate) fn solve(
    s: &Surface,
    options: &RemeshOptions,
    budget: &mut Budget,
) -> Vec<Vector3<f64>> {
    let n = s.len();
    let frames = reference_frames(s);
    // Transport r_ab per edge: z_a ~ r_ab z_b.
    let transport: Vec<C> = s
        .edges
        .iter()
        .map(|&[a, b]| {
            let alpha_ab = angle_in(&frames[a], &s.normals[a], &s.edge_vec(a, b));
            let alpha_ba = angle_in(&frames[b], &s.normals[b], &s.edge_vec(b, a));
            C::from_angle(4.0 * (alpha_ab - alpha_ba - std::f64::consts::PI))
        })
        .collect();

    let (lo, hi) = s
        .pos
        .iter()
        .fold((s.pos[0], s.pos[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let diagonal = (hi - lo).norm().max(1e-12);
    let mut weight = vec![0.0; n];
    let mut target = vec![C(0.0, 0.0); n];
    let rotation = match options.direction {
        FieldDirection::Angle(deg) => C::from_angle(4.0 * deg.to_radians()),
        _ => C(1.0, 0.0),
    };
    match options.direction {
        FieldDirection::Curvature | FieldDirection::Angle(_) => {
            let mut mark = vec![usize::MAX; n];
            // Total alignment weight comparable to the smoothness energy of a field that
            // turns once across the surface: curvature leads where it is clear, the boundary
            // and smoothness elsewhere.
            let total = CURVATURE_WEIGHT;
            for v in 0..n {
                if let Some((angle, aniso, mean)) = curvature(s, &frames, v, &mut mark) {
                    weight[v] = total / n as f64 * alignment_weight(aniso, mean, diagonal);
                    target[v] = C::from_angle(4.0 * angle).mul(rotation);
                }
            }
        }
        FieldDirection::Vector(d) => {
            let d = Vector3::new(d[0], d[1], d[2]).normalize();
            for v in 0..n {
                let nv = s.normals[v];
                let p = d - nv * nv.dot(&d);
                let len2 = p.norm_squared();
                weight[v] = 4.0 * len2;
                target[v] = C::from_angle(4.0 * angle_in(&frames[v], &nv, &p));
            }
        }
    }
    // A whisper of a global direction so a surface with no boundary and no curvature still
    // gets a definite field.
    for v in 0..n {
        let nv = s.normals[v];
        let x = any_tangent(&Vector3::z());
        let p = x - nv * nv.dot(&x);
        target[v] = target[v].add(
            C::from_angle(4.0 * angle_in(&frames[v], &nv, &p)).scale(1e-6 / (weight[v] + 1e-6)),
        );
        weight[v] += 1e-6;
    }

    let mut fixed = vec![false; n];
    let mut z = vec![C(0.0, 0.0); n];
    let aligned = s.aligned_boundary(options.boundary);
    for v in (0..n).filter(|&v| aligned[v]) {
        if let Some((din, dout)) = s.bdirs[v] {
            let nv = s.normals[v];
            let a_in = C::from_angle(4.0 * angle_in(&frames[v], &nv, &din));
            let a_out = C::from_angle(4.0 * angle_in(&frames[v], &nv, &dout));
            let sum = a_in.add(a_out);
            let zc = if sum.norm() > 0.3 {
                sum.scale(1.0 / sum.norm())
            } else {
                a_in
            };
            z[v] = zc.mul(rotation);
            fixed[v] = true;
        }
    }

    let mut rhs = vec![0.0; 2 * n];
    for v in 0..n {
        let c = target[v].scale(weight[v]);
        rhs[2 * v] = c.0;
        rhs[2 * v + 1] = c.1;
    }
    for (e, &[a, b]) in s.edges.iter().enumerate() {
        let r = transport[e];
        if fixed[b] && !fixed[a] {
            let c = r.mul(z[b]);
            rhs[2 * a] += c.0;
            rhs[2 * a + 1] += c.1;
        }
        if fixed[a] && !fixed[b] {
            let c = r.conj().mul(z[a]);
            rhs[2 * b] += c.0;
            rhs[2 * b + 1] += c.1;
        }
    }
    let mut x = vec![0.0; 2 * n];
    for v in 0..n {
        if fixed[v] {
            rhs[2 * v] = 0.0;
            rhs[2 * v + 1] = 0.0;
        } else {
            x[2 * v] = target[v].0;
            x[2 * v + 1] = target[v].1;
        }
    }
    let linear = Operator {
        s,
        transport: &transport,
        weight: &weight,
        fixed: &fixed,
        shift: 0.0,
    };
    conjugate_gradient(
        |x: &[f64], out: &mut [f64]| linear.apply(x, out),
        &rhs,
        &mut x,
        4000,
        1e-9,
        &mut |k| budget.poll(0.5 * k as f64 / 4000.0),
    );
    // Ginzburg-Landau style renormalisation (Viertel and Osting 2019): the linear solve lets
    // |z| vanish, which gathers all the boundary-forced turning into one high-order zero (a
    // polar pattern, fatal for square quads). Implicit steps towards unit crosses split it
    // into separate +1/4 cones placed where they cost least.
    let shift = GL_SHIFT;
    let relaxed = Operator { shift, ..linear };
    for round in 0..GL_STEPS {
        if !budget.poll(0.5 + 0.5 * round as f64 / GL_STEPS as f64) {
            break;
        }
        let mut step = rhs.clone();
        for v in 0..n {
            let norm = x[2 * v].hypot(x[2 * v + 1]);
            if !fixed[v] && norm > 1e-300 {
                step[2 * v] += shift * x[2 * v] / norm;
                step[2 * v + 1] += shift * x[2 * v + 1] / norm;
            }
        }
        conjugate_gradient(
            |x: &[f64], out: &mut [f64]| relaxed.apply(x, out),
            &step,
            &mut x,
            200,
            1e-6,
            &mut |_| budget.poll(0.5 + 0.5 * round as f64 / GL_STEPS as f64),
        );
    }
    (0..n)
        .map(|v| {
            let zv = if fixed[v] {
                z[v]
            } else {
                C(x[2 * v], x[2 * v + 1])
            };
            let theta = zv.1.atan2(zv.0) / 4.0;
            let nv = s.normals[v];
            let e = frames[v];
            (e * theta.cos() + nv.cross(&e) * theta.sin()).normalize()
        })
        .collect()
}

/// Total weight of curvature alignment, in units of the smoothness energy of a field that
/// turns once across the surface.
const CURVATURE_WEIGHT: f64 = 40.0;

/// Number and strength of the renormalising steps.
const GL_STEPS: usize = 15;
const GL_SHIFT: f64 = 0.5;

/// The field energy's normal-equation operator, with an optional diagonal shift.
#[derive(Clone, Copy)]
struct Operator<'a> {
    s: &'a Surface,
    transport: &'a [C],
    weight: &'a [f64],
    fixed: &'a [bool],
    shift: f64,
}

impl Operator<'_> {
    fn apply(&self, x: &[f64], out: &mut [f64]) {
        let n = self.s.len();
        for v in 0..n {
            let d = self.weight[v] + self.shift;
            out[2 * v] = d * x[2 * v];
            out[2 * v + 1] = d * x[2 * v + 1];
        }
        for (e, &[a, b]) in self.s.edges.iter().enumerate() {
            let r = self.transport[e];
            let za = if self.fixed[a] {
                C(0.0, 0.0)
            } else {
                C(x[2 * a], x[2 * a + 1])
            };
            let zb = if self.fixed[b] {
                C(0.0, 0.0)
            } else {
                C(x[2 * b], x[2 * b + 1])
            };
            let ra = za.add(r.mul(zb).scale(-1.0));
            let rb = zb.add(r.conj().mul(za).scale(-1.0));
            out[2 * a] += ra.0;
            out[2 * a + 1] += ra.1;
            out[2 * b] += rb.0;
            out[2 * b + 1] += rb.1;
        }
        for v in 0..n {
            if self.fixed[v] {
                out[2 * v] = x[2 * v];
                out[2 * v + 1] = x[2 * v + 1];
            }
        }
    }
}

/// Re-pins the crosses of aligned boundary vertices of a refined surface onto its boundary tangents
/// (refinement interpolates them, which is close but not exact).
pub(crate) fn snap_boundary(
    s: &Surface,
    aligned: &[bool],
    frames: &mut [Vector3<f64>],
    rotation_deg: f64,
) {
    for v in (0..s.len()).filter(|&v| aligned[v]) {
        if let Some((din, dout)) = s.bdirs[v] {
            let n = s.normals[v];
            let tin = (din - n * n.dot(&din)).try_normalize(1e-300);
            let tout = (dout - n * n.dot(&dout)).try_normalize(1e-300);
            let tangent = match (tin, tout) {
                (Some(a), Some(b)) => {
                    let b = match_rosy(&a, &b, &n);
                    (a + b).try_normalize(1e-300).unwrap_or(a)
                }
                (Some(a), None) | (None, Some(a)) => a,
                (None, None) => continue,
            };
            let r = rotation_deg.to_radians();
            frames[v] = (tangent * r.cos() + n.cross(&tangent) * r.sin()).normalize();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn umbilic_points_get_no_curvature_weight_at_any_scale() {
        // Spheres of radius 3 and 20 (k1 = k2 = 1/R, |H| = 1/R), a plane, and an apparent
        // anisotropy of a few per cent of the curvature (noise of the fit): all zero.
        for radius in [3.0, 20.0] {
            let k = 1.0 / radius;
            let extent = 2.0 * radius;
            assert_eq!(alignment_weight(0.0, k, extent), 0.0);
            assert_eq!(alignment_weight(0.04 * k, k, extent), 0.0);
        }
        assert_eq!(alignment_weight(0.0, 0.0, 10.0), 0.0);
    }

    #[test]
    fn anisotropic_points_keep_their_weight_and_it_is_scale_invariant() {
        // Hypar (k1 = -k2, H = 0): nearly full weight; barrel vault (k2 = 0): a^2, a = 2/3.
        let hypar = alignment_weight(2.0, 0.0, 100.0);
        assert!(hypar > 0.9, "{hypar}");
        let barrel = alignment_weight(1.0, 0.5, 1e9);
        assert!((barrel - 4.0 / 9.0).abs() < 1e-6, "{barrel}");
        // Scaling the model by s scales curvatures by 1/s and the extent by s.
        for (aniso, mean, extent) in [(0.3, 1.0, 6.0), (1.0, 0.5, 4.0), (0.08, 1.0, 10.0)] {
            let w = alignment_weight(aniso, mean, extent);
            for s in [0.01, 3.0, 1000.0] {
                let scaled = alignment_weight(aniso / s, mean / s, extent * s);
                assert!((scaled - w).abs() < 1e-12, "{w} vs {scaled} at scale {s}");
            }
        }
        // Monotone and continuous through the umbilic threshold.
        let mut last = 0.0;
        for k in 0..=200 {
            let w = alignment_weight(k as f64 * 0.005, 1.0, 1e9);
            assert!(w >= last - 1e-15);
            assert!(w - last < 0.02);
            last = w;
        }
    }
}
