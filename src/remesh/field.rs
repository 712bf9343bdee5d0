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
//!
//! A designer's field ([`super::UserField`], the force flow of the paper's section 4.4)
//! enters the same energy as a second data term: with share `s`, `w_i |z_i - c_i|^2` becomes
//! `a_i |z_i - u_i|^2 + b_i |z_i - c_i|^2`, `a_i = W s q_i`, `b_i = W (1 - s) w'_i`, where
//! `u_i` is the user cross at vertex `i` (the mean fourth power of the vectors there, per
//! face vectors counted at their corners by area), `q_i` how clear it is ([`user_cross`]) and
//! `w'_i` whether the other source has a direction there at all (`principal_defined`). Both terms are one quadratic term with target
//! `(a u + b c) / (a + b)`, so the smoothing below is the same for every source. Guide curves
//! ([`super::GuideCurves`]) are one more such term: at a vertex whose guide samples fall off
//! to `f` (1 on a curve, 0 at its reach), with share `s_g`, the curve's tangent gets
//! `g = W s_g f q_i` and every other term keeps `1 - s_g f` of its weight.

use nalgebra::{Matrix2, Matrix5, Vector3, Vector5};

use super::budget::Budget;
use super::linalg::conjugate_gradient;
use super::multigrid::{BlockMatrix, Multigrid};
use super::surface::{Surface, any_tangent, in_tangent_plane};
use super::user_field::Samples;
use super::{FieldDirection, RemeshOptions};
use crate::parallel::Scatter;

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

/// The principal curvature at a vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Principal {
    /// A principal direction (unit tangent; the other is perpendicular), read at the
    /// tile's scale.
    pub dir: Vector3<f64>,
    /// The same read over the 2-ring alone: where the surface is umbilic at the tile's scale
    /// the field's whisper term is summed with it (see [`solve`]).
    pub local_dir: Vector3<f64>,
    /// `|k1 - k2|`.
    pub aniso: f64,
    /// `|k1 + k2| / 2`.
    pub mean: f64,
}

/// The principal curvature at every vertex of `s`, read over a disc of radius `reach`
/// ([`curvature`]; `None` where too few neighbours fix it). The fit is made at sites a
/// [`SITES_PER_REACH`]th of the reach apart, and every vertex within that of a site takes
/// its reading (its direction laid into the vertex's tangent plane): on a mesh much finer
/// than the quads a fit at every vertex would walk thousands of vertices for each. The
/// 2-ring's direction ([`Principal::local_dir`]) is read at every vertex.
pub(crate) fn principal_curvatures(s: &Surface, reach: f64) -> Vec<Option<Principal>> {
    let frames = reference_frames(s);
    let n = s.len();
    let along = |v: usize, angle: f64| {
        let e = frames[v];
        e * angle.cos() + s.normals[v].cross(&e) * angle.sin()
    };
    // Sites, in vertex order: a vertex no earlier site's small neighbourhood holds is one.
    let mut mark = vec![usize::MAX; n];
    let mut site = vec![usize::MAX; n];
    let mut sites = Vec::new();
    for v in 0..n {
        if site[v] != usize::MAX {
            continue;
        }
        site[v] = sites.len();
        for w in neighbourhood(s, v, reach / SITES_PER_REACH, 0, v, &mut mark) {
            if site[w] == usize::MAX {
                site[w] = sites.len();
            }
        }
        sites.push(v);
    }
    // The fits, each on its own (on the threads of `parallel`, each part with its own marks;
    // a search's stamp is its vertex, so no two searches of a part share one).
    let scratch = || vec![usize::MAX; n];
    let fits = crate::parallel::map_with(sites.len(), scratch, |mark, k| {
        let v = sites[k];
        let near = neighbourhood(s, v, reach, 2, v, mark);
        curvature(s, &frames, v, &near, true)
            .map(|(angle, aniso, mean)| (along(v, angle), aniso, mean))
    });
    crate::parallel::map_with(n, scratch, |mark, v| {
        let ring = neighbourhood(s, v, 0.0, 2, v, mark);
        let reading = fits[site[v]].zip(curvature(s, &frames, v, &ring, false));
        reading.map(|((dir, aniso, mean), (local, _, _))| {
            let nv = s.normals[v];
            Principal {
                dir: in_tangent_plane(&dir, &nv),
                local_dir: along(v, local),
                aniso,
                mean,
            }
        })
    })
}

/// How far around a vertex its curvature is read, in target quad edges: a tile spans two
/// quads, so the courses should follow the surface's bending over a tile, not over its
/// triangles. A mesh faceted coarser than its triangles (a sphere meshed in
/// latitude-longitude rows and then remeshed evenly, an STL of a NURBS surface) bends at its
/// facets' creases, and a fit over the triangles' 2-ring reads those creases as principal
/// directions: on such a hemisphere (facets of 196 mm, triangles of 98 mm) 29 % of the
/// vertices read as anisotropic and the field turned into rings along the rim (83 irregular
/// vertices instead of 16 on the same hemisphere meshed in rows); read over three quad
/// edges, none does (two leave rings near the rim, four gain nothing: docs/journal.md, *Curvature
/// read at the tile's scale*).
pub(crate) const CURVATURE_REACH: f64 = 3.0;

/// Most vertices a curvature fit sums (see [`curvature`]): on a mesh of 12 mm triangles
/// read over three 150 mm quad edges, about one in twenty.
const MAX_FIT_POINTS: usize = 192;

/// Curvature sites per reach (see [`principal_curvatures`]): a site's reading serves the
/// vertices within an eighth of the reach, three eighths of a quad edge, so on a mesh
/// whose edges are longer than that every vertex is read on its own. A quarter of the reach
/// (sites sharing readings on every mesh of the measured set) left readings that jump from
/// cell to cell: 42 more tiles cut to fit over the 51 runs of the README's table.
const SITES_PER_REACH: f64 = 8.0;

/// The vertices other than `v` reached from it by edges, each within `reach` of `v` or at
/// most `rings` edges from it, in the walk's order of rings. `mark` is scratch space, one
/// entry per vertex, where the vertices reached are marked with `stamp` (a value no other
/// call uses).
fn neighbourhood(
    s: &Surface,
    v: usize,
    reach: f64,
    rings: usize,
    stamp: usize,
    mark: &mut [usize],
) -> Vec<usize> {
    let mut near = Vec::new();
    mark[v] = stamp;
    let mut ring = 0;
    let mut front = vec![v];
    let mut next = Vec::new();
    while !front.is_empty() {
        ring += 1;
        for &u in &front {
            for &(w, _) in &s.adj[u] {
                if mark[w] != stamp && (ring <= rings || (s.pos[w] - s.pos[v]).norm() < reach) {
                    mark[w] = stamp;
                    near.push(w);
                    next.push(w);
                }
            }
        }
        std::mem::swap(&mut front, &mut next);
        next.clear();
    }
    near
}

/// Principal curvature direction (angle in the vertex frame) and anisotropy `|k1 - k2|`,
/// from a least-squares quadric `h = A x^2 + B xy + C y^2 + D x + E y` over the vertices
/// `near` `v` (at most [`MAX_FIT_POINTS`] of them, evenly in their order); `weighted`, by
/// `(1 - (d / r)^2)^2` (`r` a little beyond the farthest of them, so that the fit changes
/// smoothly from vertex to vertex).
fn curvature(
    s: &Surface,
    frames: &[Vector3<f64>],
    v: usize,
    near: &[usize],
    weighted: bool,
) -> Option<(f64, f64, f64)> {
    let n = s.normals[v];
    let e = frames[v];
    let b = n.cross(&e);
    if near.len() < 5 {
        return None;
    }
    let farthest = near
        .iter()
        .map(|&w| (s.pos[w] - s.pos[v]).norm())
        .fold(0.0, f64::max);
    let r2 = (1.25 * farthest).powi(2);
    let mut m = Matrix5::zeros();
    let mut rhs = Vector5::zeros();
    // On a mesh much finer than the quads the reach holds thousands of vertices; an even
    // share of them, in the walk's order of rings, fixes the quadric as well.
    let stride = near.len().div_ceil(MAX_FIT_POINTS);
    for &w in near.iter().step_by(stride) {
        let d = s.edge_vec(v, w);
        let weight = if weighted {
            (1.0 - d.norm_squared() / r2).powi(2)
        } else {
            1.0
        };
        let (x, y, h) = (d.dot(&e), d.dot(&b), d.dot(&n));
        let row = Vector5::new(x * x, x * y, y * y, x, y);
        m += row * row.transpose() * weight;
        rhs += row * (h * weight);
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
/// that ([`principal_defined`]). `extent` is the surface's size (its bounding-box diagonal),
/// which keeps nearly flat parts from reading as anisotropic. Every term is a curvature
/// (1 / length), so the weight does not change when the model is scaled: a 3 m and a 20 m
/// dome are treated alike.
fn alignment_weight(aniso: f64, mean: f64, extent: f64) -> f64 {
    let rel = relative_anisotropy(aniso, mean, extent);
    let ramp = umbilic_ramp(rel);
    rel * rel * ramp * ramp * (3.0 - 2.0 * ramp)
}

/// 0 below [`UMBILIC`] relative anisotropy, 1 above twice that, linear in between.
fn umbilic_ramp(rel: f64) -> f64 {
    ((rel - UMBILIC) / UMBILIC).clamp(0.0, 1.0)
}

/// The relative anisotropy `a` of [`alignment_weight`] (0 where it is not a number).
fn relative_anisotropy(aniso: f64, mean: f64, extent: f64) -> f64 {
    let rel = aniso / (aniso + mean + 4.0 / extent);
    if rel.is_finite() { rel } else { 0.0 }
}

/// Whether the principal directions mean anything, in `[0, 1]`: 0 below [`UMBILIC`]
/// relative anisotropy, 1 above twice that, smooth in between. A designer's field is blended
/// with the curvature field by this (the curvature then counts fully at its share wherever
/// it has a direction at all).
fn principal_defined(aniso: f64, mean: f64, extent: f64) -> f64 {
    let ramp = umbilic_ramp(relative_anisotropy(aniso, mean, extent));
    ramp * ramp * (3.0 - 2.0 * ramp)
}

/// Relative anisotropy below which a point counts as umbilic (see [`alignment_weight`]).
const UMBILIC: f64 = 0.05;

/// Solves the orientation field on `s`; returns one unit tangent per vertex (any of the four
/// directions of its cross). `user` is the designer's field (samples and share), `guides` the
/// guide curves' samples (weighted by their fall-off) and share; `principal` the principal
/// curvatures per vertex when they are not to be read from `s` itself (a subdivided coarse
/// input, [`super::refine::subdivide_coarse`]).
/// Stops early (with a usable but less smooth field) once `budget` says so.
pub(crate) fn solve(
    s: &Surface,
    options: &RemeshOptions,
    principal: Option<&[Option<Principal>]>,
    user: Option<&(Samples, f64)>,
    guides: Option<&(Samples, f64)>,
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
    // Per vertex: how clearly the source of `direction` points (in [0, 1]), whether it has
    // a direction at all (the same for a global vector; for a blend with a user field) and
    // where it points.
    let mut clarity = vec![0.0; n];
    let mut defined = vec![0.0; n];
    let mut target = vec![C(0.0, 0.0); n];
    let rotation = match options.direction {
        FieldDirection::Angle(deg) => C::from_angle(4.0 * deg.to_radians()),
        _ => C(1.0, 0.0),
    };
    let strength = match options.direction {
        FieldDirection::Curvature | FieldDirection::Angle(_) => {
            let own;
            let principal = match principal {
                Some(p) => p,
                None => {
                    own = principal_curvatures(s, CURVATURE_REACH * options.target_edge);
                    &own
                }
            };
            for (v, p) in principal.iter().enumerate() {
                if let Some(p) = p {
                    clarity[v] = alignment_weight(p.aniso, p.mean, diagonal);
                    // Where the surface is umbilic at the tile's scale the direction only
                    // meets the whisper below; the 2-ring's is kept there (see
                    // [`CURVATURE_REACH`]).
                    let dir = if clarity[v] > 0.0 {
                        &p.dir
                    } else {
                        &p.local_dir
                    };
                    let angle = angle_in(&frames[v], &s.normals[v], dir);
                    defined[v] = principal_defined(p.aniso, p.mean, diagonal);
                    target[v] = C::from_angle(4.0 * angle).mul(rotation);
                }
            }
            // Total alignment weight comparable to the smoothness energy of a field that
            // turns once across the surface: curvature leads where it is clear, the boundary
            // and smoothness elsewhere.
            CURVATURE_WEIGHT / n as f64
        }
        FieldDirection::Vector(d) => {
            let d = Vector3::new(d[0], d[1], d[2]).normalize();
            for v in 0..n {
                let nv = s.normals[v];
                let p = d - nv * nv.dot(&d);
                clarity[v] = p.norm_squared();
                defined[v] = clarity[v];
                target[v] = C::from_angle(4.0 * angle_in(&frames[v], &nv, &p));
            }
            VECTOR_WEIGHT
        }
        FieldDirection::Smooth => 0.0,
    };
    let mut weight: Vec<f64> = clarity.iter().map(|c| c * strength).collect();
    if let Some((samples, share)) = user {
        for v in 0..n {
            let (z, clear) = user_cross(&frames[v], &s.normals[v], &samples[v]);
            // Both sources held firmly, in proportion to the share.
            let a = USER_WEIGHT * share * clear;
            let b = USER_WEIGHT * (1.0 - share) * defined[v];
            (target[v], weight[v]) = blend(z.mul(rotation), a, target[v], b);
        }
    }
    if let Some((samples, share)) = guides {
        for v in 0..n {
            // Near a curve its share is `share` times the fall-off of its samples; the other
            // sources keep the rest of their weight.
            let near = samples[v]
                .iter()
                .fold(0.0f64, |m, &(_, w)| m.max(w))
                .min(1.0);
            if near > 0.0 {
                let (z, clear) = user_cross(&frames[v], &s.normals[v], &samples[v]);
                let g = share * near;
                let a = GUIDE_WEIGHT * g * clear;
                let b = weight[v] * (1.0 - g);
                (target[v], weight[v]) = blend(z.mul(rotation), a, target[v], b);
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
    let aligned = s.aligned_boundary(options.effective_boundary());
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

    // Each pull stands for the area around its vertex: weighted by that area, relative to
    // the mean, the pulls integrate over the surface, and a part of it meshed finely (the
    // rows of a latitude-longitude dome closing towards the pole, a shell's denser bands)
    // does not pull harder than the same part meshed coarsely. (The renormalising shift
    // below stays one per vertex: weighted by area too, it lets the quads of a folded
    // corner span the fold, `tests/remesh.rs`.)
    for (w, a) in weight.iter_mut().zip(relative_areas(s)) {
        *w *= a;
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
    let scatter = Scatter::default();
    let linear = Operator {
        s,
        transport: &transport,
        weight: &weight,
        fixed: &fixed,
        shift: 0.0,
        scatter: &scatter,
    };
    let cycle = linear.multigrid();
    conjugate_gradient(
        |x: &[f64], out: &mut [f64]| linear.apply(x, out),
        &rhs,
        &mut x,
        4000,
        1e-9,
        Some(&|r: &[f64], z: &mut [f64]| cycle.precondition(r, z)),
        &mut |k| budget.poll(0.5 * k as f64 / 4000.0),
    );
    // Ginzburg-Landau style renormalisation (Viertel and Osting 2019): the linear solve lets
    // |z| vanish, which gathers all the boundary-forced turning into one high-order zero (a
    // polar pattern, fatal for square quads). Implicit steps towards unit crosses split it
    // into separate +1/4 cones placed where they cost least.
    let shift = options.renormalisation;
    let relaxed = Operator { shift, ..linear };
    let cycle = relaxed.multigrid();
    let steps = if shift > 0.0 { GL_STEPS } else { 0 };
    for round in 0..steps {
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
            Some(&|r: &[f64], z: &mut [f64]| cycle.precondition(r, z)),
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

/// Two data terms `a |z - u|^2 + b |z - c|^2` as one, `(a + b) |z - (a u + b c) / (a + b)|^2`
/// (up to a constant): the target and its weight. With no weight the target `c` is kept.
fn blend(u: C, a: f64, c: C, b: f64) -> (C, f64) {
    if a + b > 0.0 {
        (u.scale(a).add(c.scale(b)).scale(1.0 / (a + b)), a + b)
    } else {
        (c, 0.0)
    }
}

/// The cross a vertex's user samples ask for and how clearly, in `[0, 1]`: the weighted
/// mean of their fourth powers (so opposite and perpendicular vectors agree), each counted by
/// the square of its tangential part; its modulus is 1 only when all samples are tangent and
/// agree modulo 90 degrees, and falls where they are nearly normal or disagree (around a
/// singular point of the given field), leaving those vertices to smoothness.
fn user_cross(e: &Vector3<f64>, n: &Vector3<f64>, samples: &[(Vector3<f64>, f64)]) -> (C, f64) {
    let mut sum = C(0.0, 0.0);
    let mut total = 0.0;
    for (d, w) in samples {
        let p = d - n * n.dot(d);
        sum = sum.add(C::from_angle(4.0 * angle_in(e, n, &p)).scale(w * p.norm_squared()));
        total += w;
    }
    let norm = sum.norm();
    if total > 0.0 && norm > 1e-12 * total {
        (sum.scale(1.0 / norm), (norm / total).min(1.0))
    } else {
        (C(1.0, 0.0), 0.0)
    }
}

/// Alignment weight per vertex of a global direction ([`FieldDirection::Vector`]), against
/// the smoothness energy of one edge.
const VECTOR_WEIGHT: f64 = 4.0;

/// Alignment weight per vertex of the user field at full share, against the smoothness
/// energy of one edge: firm enough that the crosses follow the given directions, loose
/// enough to smooth out noise over a ring or two of the input.
const USER_WEIGHT: f64 = 1.0;

/// Alignment weight per vertex of a guide curve on the curve, at full share: a curve touches
/// a band of a few vertices only, so it is held firmer than the designer's field (which pulls
/// everywhere), enough to turn the crosses in its band against a field at a fifth of its share.
const GUIDE_WEIGHT: f64 = 8.0;

/// Total weight of curvature alignment, in units of the smoothness energy of a field that
/// turns once across the surface.
const CURVATURE_WEIGHT: f64 = 40.0;

/// Number of the renormalising steps (their strength is
/// [`RemeshOptions::renormalisation`]).
const GL_STEPS: usize = 15;

/// Per vertex, its area ([`Surface::vertex_areas`]) relative to the mean vertex area: 1
/// everywhere on an even triangulation.
fn relative_areas(s: &Surface) -> Vec<f64> {
    let area = s.vertex_areas();
    let mean = area.iter().sum::<f64>() / area.len().max(1) as f64;
    if mean > 0.0 {
        area.iter().map(|a| a / mean).collect()
    } else {
        vec![1.0; area.len()]
    }
}

/// The field energy's normal-equation operator, with an optional diagonal shift.
#[derive(Clone, Copy)]
struct Operator<'a> {
    s: &'a Surface,
    transport: &'a [C],
    /// Per vertex, the weight of its pull (times its relative area, [`relative_areas`]).
    weight: &'a [f64],
    fixed: &'a [bool],
    shift: f64,
    /// Where the edges' terms are summed, part by part.
    scatter: &'a Scatter,
}

impl Operator<'_> {
    /// The multigrid cycle that preconditions this operator's solves.
    fn multigrid(&self) -> Multigrid {
        let matrix = BlockMatrix::connection(
            self.s.len(),
            &self.s.edges,
            |e| {
                let C(re, im) = self.transport[e];
                (1.0, Matrix2::new(re, -im, im, re))
            },
            |v| self.weight[v] + self.shift,
        );
        let held: Vec<bool> = self.fixed.iter().flat_map(|&f| [f, f]).collect();
        Multigrid::new(matrix, &held)
    }

    fn apply(&self, x: &[f64], out: &mut [f64]) {
        let n = self.s.len();
        for v in 0..n {
            let d = self.weight[v] + self.shift;
            out[2 * v] = d * x[2 * v];
            out[2 * v + 1] = d * x[2 * v + 1];
        }
        let (edges, transport, fixed) = (&self.s.edges, self.transport, self.fixed);
        self.scatter.add(edges.len(), out, |range, out| {
            for (&[a, b], &r) in edges[range.clone()].iter().zip(&transport[range]) {
                let za = if fixed[a] {
                    C(0.0, 0.0)
                } else {
                    C(x[2 * a], x[2 * a + 1])
                };
                let zb = if fixed[b] {
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
        });
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

    /// Worst and mean deviation (degrees, modulo 90) of the solved crosses from `want` over
    /// the vertices at least `skip` from the point `(0, 0, top)`.
    fn deviation(
        s: &Surface,
        frames: &[Vector3<f64>],
        want: impl Fn(&Vector3<f64>) -> Vector3<f64>,
        top: f64,
        skip: f64,
    ) -> (f64, f64) {
        let (mut worst, mut sum, mut count) = (0.0f64, 0.0, 0);
        for (v, o) in frames.iter().enumerate() {
            if (s.pos[v] - Vector3::new(0.0, 0.0, top)).norm() < skip {
                continue;
            }
            let n = s.normals[v];
            let w = want(&s.pos[v]);
            let w = w - n * n.dot(&w);
            let a = (o.dot(&w).abs() / w.norm()).min(1.0).acos().to_degrees();
            let d = a.min(90.0 - a);
            worst = worst.max(d);
            sum += d;
            count += 1;
        }
        (worst, sum / count as f64)
    }

    #[test]
    fn the_solved_field_follows_a_user_field_on_a_dome() {
        use crate::mesh::generate::spherical_cap;
        let (radius, fraction) = (3.0, 0.3);
        let cap = spherical_cap(radius, fraction, 0.1);
        let (s, map) = Surface::from_polymesh_mapped(&cap).unwrap();
        let centre = Vector3::new(0.0, 0.0, -radius * (1.0 - 2.0 * fraction));
        let top = radius + centre.z;
        for turn in [0.0f64, 30.0] {
            let want = |p: &Vector3<f64>| {
                let r = p - centre;
                let n = r.normalize();
                let m = Vector3::new(r.x * r.z, r.y * r.z, -(r.x * r.x + r.y * r.y));
                let m = m.try_normalize(1e-12).unwrap_or_else(Vector3::x);
                let a = turn.to_radians();
                m * a.cos() + n.cross(&m) * a.sin()
            };
            let vectors = cap
                .positions()
                .iter()
                .map(|p| want(&p.coords).into())
                .collect();
            let user = super::super::UserField::for_mesh(&cap, vectors, 1.0).unwrap();
            let samples = (user.samples(&cap, &map, s.len()), 1.0);
            let mut control = crate::control::Control::none();
            let mut budget = Budget::new(
                &mut control,
                std::time::Instant::now(),
                std::time::Duration::from_secs(60),
            );
            let frames = solve(
                &s,
                &RemeshOptions::default(),
                None,
                Some(&samples),
                None,
                &mut budget,
            );
            // Away from the crown (where the meridians meet and no cross field can follow
            // them) the crosses are on the given directions.
            let (worst, mean) = deviation(&s, &frames, want, top, 0.5);
            assert!(
                worst < 3.0 && mean < 0.5,
                "turn {turn}: worst {worst:.2} mean {mean:.2}"
            );
            // Without the user field the umbilic dome's crosses go their own way.
            let free = solve(&s, &RemeshOptions::default(), None, None, None, &mut budget);
            let (_, mean) = deviation(&s, &free, want, top, 0.5);
            assert!(mean > 10.0, "turn {turn}: mean {mean:.2} by chance");
        }
    }

    /// Solves the field on a barrel vault (axis along y, principal directions along x and
    /// y) against a user field turned 20 degrees from the axis, with the given share; the
    /// mean angle of the crosses from the axis, modulo 90 degrees, in `[-45, 45]`.
    fn barrel_angle(share: f64) -> f64 {
        use crate::remesh::BoundaryAlignment;
        use crate::remesh::surface::samples::sheet;
        let s = sheet(20, 0.1, (0..0, 0..0), |x, _| {
            (4.0f64 - (x - 1.0) * (x - 1.0)).sqrt()
        });
        let turn = 20f64.to_radians();
        let user: Vec<Vec<(Vector3<f64>, f64)>> = (0..s.len())
            .map(|_| vec![(Vector3::new(turn.sin(), turn.cos(), 0.0), 1.0)])
            .collect();
        let options = RemeshOptions {
            boundary: BoundaryAlignment::Never,
            ..RemeshOptions::default()
        };
        let mut control = crate::control::Control::none();
        let mut budget = Budget::new(
            &mut control,
            std::time::Instant::now(),
            std::time::Duration::from_secs(60),
        );
        let frames = solve(&s, &options, None, Some(&(user, share)), None, &mut budget);
        let mut sum = 0.0;
        for (v, o) in frames.iter().enumerate() {
            let o = match_rosy(&Vector3::y(), o, &s.normals[v]);
            // Angle from the axis (y) towards +x, seen in the tangent plane.
            sum += o.x.atan2(o.y).to_degrees();
        }
        sum / s.len() as f64
    }

    #[test]
    fn the_share_blends_the_user_field_with_the_curvature_field() {
        let (none, half, full) = (barrel_angle(0.0), barrel_angle(0.5), barrel_angle(1.0));
        assert!(none.abs() < 2.0, "share 0: {none:.2} degrees from the axis");
        assert!(
            (full - 20.0).abs() < 2.0,
            "share 1: {full:.2} degrees from the axis"
        );
        assert!(
            half > none + 3.0 && half < full - 3.0,
            "share 0.5: {half:.2} (0: {none:.2}, 1: {full:.2})"
        );
    }
}
