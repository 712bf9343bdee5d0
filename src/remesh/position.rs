//! The isotropic position (lattice) field (Instant Meshes section 5; the paper's step 2).
//!
//! Every vertex `i` carries a lattice origin `q_i = p_i + F_i u_i`, with `F_i` its cross
//! frame and `u_i` a 2D offset: the lattice `q_i + t Z o_i + t Z o'_i` is the local grid of
//! quad corners. Neighbouring lattices should agree up to a whole lattice step `m_ab` (an
//! integer vector), which gives the least-squares energy
//!
//! `sum_edges | F_a^T (p_b - p_a) + F_a^T F_b u_b - u_a - t m_ab |^2`.
//!
//! Instant Meshes minimises it by local rounding sweeps over a hierarchy; here, as in
//! QuadriFlow's global treatment of the integer offsets, the jumps `m_ab` are held fixed
//! while one conjugate-gradient solve relaxes all offsets at once, then offsets are rounded
//! back into their cells and the jumps re-read; a few rounds settle it. On the boundary the
//! offset across the boundary is pinned to zero (a lattice line runs along the boundary),
//! and at corners both offsets are, which is what lets extraction put quad vertices exactly
//! on the boundary.

use std::collections::VecDeque;

use nalgebra::{Matrix2, Matrix3x2, Point3, Vector2, Vector3};

use super::CourseQuads;
use super::budget::Budget;
use super::flow::Jumps;
use super::linalg::conjugate_gradient;
use super::scale;
use super::surface::Surface;
use crate::mesh::PolyMesh;
use crate::mesh::simplify::simplify_mapped;
use crate::parallel::Scatter;

/// The solved lattice: origins and per-edge integer offsets.
#[derive(Debug, Clone)]
pub(crate) struct Lattice {
    /// Lattice origin (a quad corner) nearest to each vertex, in 3D.
    pub origin: Vec<Vector3<f64>>,
    /// Per edge `[a, b]` (a < b): the lattice step from a's corner to b's, in a's frame.
    pub offset: Vec<[i64; 2]>,
    /// Per vertex: 0 interior, 1 on a boundary lattice line, 2 a pinned corner.
    pub pinned: Vec<u8>,
    /// The lattice kept is the one solved from the coarse start ([`coarse_start`]).
    pub coarse_start: bool,
}

/// Solve-round-cancel rounds; the boundary is pinned from round [`PIN_FROM`] on, so the
/// lattice first finds its own structure.
const ROUNDS: usize = 4;

/// First round with the boundary pinned.
const PIN_FROM: usize = 2;

/// Conjugate-gradient iterations per round; each round starts from the previous solution.
const ITERATIONS: usize = 150;

/// Conjugate-gradient iterations of the last round.
const LAST_ITERATIONS: usize = 300;

/// Farthest (in quad lengths `t`) a dislocation is walked to cancel it against another or
/// through the boundary. Farther apart, cancelling would strain every quad in between (a
/// bend needs its extra rows), so the pair is kept as irregular vertices.
const CANCEL_REACH: f64 = 5.0;

/// Farthest (in quad lengths `t`) an unwanted lone dislocation is walked out through the
/// boundary while the boundary is still free (the rounds before [`PIN_FROM`]).
///
/// The first lattice comes from integrating along a breadth-first tree, and on an evenly
/// triangulated shell (a remeshed or scanned surface, an STL) it holds dislocations several
/// metres inside the boundary that a structured triangulation of the same shell never gets,
/// and that no later round moves: the least-squares solve relaxes around them. Each would
/// become a pair of irregular vertices. Those the surface and the field do not ask for
/// ([`JUDGE_RADIUS`]) leave while the boundary is free, which costs the lattice little.
const FREE_EXIT_REACH: f64 = 15.0;

/// Radius (in quad lengths) of the patch over which a dislocation's Burgers vector is
/// weighed against the dislocation density the surface and field ask for.
const JUDGE_RADIUS: f64 = 2.0;

/// Largest log-scale of the first lattice's spacing ([`scale`], [`integrate`]): rows may
/// start about a tenth closer or farther apart than `t` (exp(0.1) = 1.105), inside the
/// +-20 % the remesher promises.
const SCALE_LIMIT: f64 = 0.1;

/// Distance between the centroids of two triangles sharing an edge, per unit of mean edge
/// length (equilateral triangles: 1 / sqrt 3).
const TRIANGLE_STEP: f64 = 0.577;

/// Cross frames `(o, n x o)` per vertex.
pub(crate) fn bases(s: &Surface, frames: &[Vector3<f64>]) -> Vec<Matrix3x2<f64>> {
    (0..s.len())
        .map(|v| Matrix3x2::from_columns(&[frames[v], s.normals[v].cross(&frames[v])]))
        .collect()
}

/// Per edge `[a, b]`: the transfer of `b`'s frame coordinates into `a`'s, and the edge
/// vector in `a`'s tangent frame at full length (projection alone would shorten edges on
/// curved surfaces and shrink the lattice).
pub(crate) fn edge_frames(
    s: &Surface,
    basis: &[Matrix3x2<f64>],
) -> (Vec<Matrix2<f64>>, Vec<Vector2<f64>>) {
    s.edges
        .iter()
        .map(|&[a, b]| {
            let d = s.edge_vec(a, b);
            let p = basis[a].transpose() * d;
            (
                basis[a].transpose() * basis[b],
                p.try_normalize(1e-300).map_or(p, |dir| dir * d.norm()),
            )
        })
        .unzip()
}

/// Solves the lattice of spacing `t` for the cross field `frames` on `s`.
/// Stops early (with an unfinished lattice the caller must discard) once `budget` says so.
///
/// When the lattice comes out stretched ([`STRETCHED`]), it is solved again from a first
/// lattice found on a coarser copy of the surface ([`coarse_start`]) and the one with fewer
/// strained edges is kept.
pub(crate) fn solve(
    s: &Surface,
    frames: &[Vector3<f64>],
    t: f64,
    courses: Option<&CourseQuads>,
    pin: &[bool],
    budget: &mut Budget,
) -> Lattice {
    solve_level(s, frames, t, courses, pin, budget, true)
}

/// [`solve`], trying the coarse start only when `coarse` says so (not on the coarse copy).
fn solve_level(
    s: &Surface,
    frames: &[Vector3<f64>],
    t: f64,
    courses: Option<&CourseQuads>,
    pin: &[bool],
    budget: &mut Budget,
    coarse: bool,
) -> Lattice {
    let n = s.len();
    let basis = bases(s, frames);
    let (transfer, delta) = edge_frames(s, &basis);
    let sp = spacings(s, &basis, t, courses);

    let mut pinned = vec![0u8; n];
    let mut fixed = vec![false; 2 * n];
    for v in (0..n).filter(|&v| pin[v] && s.boundary[v].is_some()) {
        fixed[2 * v + 1] = true;
        pinned[v] = 1;
        if s.is_corner(v) {
            fixed[2 * v] = true;
            pinned[v] = 2;
        }
    }

    let read = |u: &[f64], v: usize| Vector2::new(u[2 * v], u[2 * v + 1]);
    let jumps = |u: &[f64]| -> Vec<[i64; 2]> {
        s.edges
            .iter()
            .enumerate()
            .map(|(e, &[a, b])| {
                let r = (delta[e] + transfer[e] * read(u, b) - read(u, a)).component_div(&sp[a]);
                [r.x.round() as i64, r.y.round() as i64]
            })
            .collect()
    };
    // Offsets back into their lattice cells (held components to zero) before jumps are read.
    let into_cells = |u: &mut [f64], active: &[bool]| {
        for (k, (x, &held)) in u.iter_mut().zip(active).enumerate() {
            let t = sp[k / 2][k % 2];
            *x = if held { 0.0 } else { *x - t * (*x / t).round() };
        }
    };
    let flow = Jumps::new(s, &transfer);
    let mean_edge = s
        .edges
        .iter()
        .map(|&[a, b]| s.edge_vec(a, b).norm())
        .sum::<f64>()
        / s.edges.len().max(1) as f64;
    // The reach in steps between triangles.
    let depth = (CANCEL_REACH * t / (TRIANGLE_STEP * mean_edge).max(f64::MIN_POSITIVE))
        .ceil()
        .min(1e6) as usize;
    let weight = edge_weights(s);
    let system = System {
        s,
        transfer: &transfer,
        delta: &delta,
        weight: &weight,
        sp: &sp,
    };
    // Before the boundary is pinned, unwanted lone dislocations leave through it from
    // farther in.
    let density = burgers_density(s, &delta, &transfer, t);
    let free = (
        (FREE_EXIT_REACH / CANCEL_REACH * depth as f64).ceil() as usize,
        density.as_slice(),
        (JUDGE_RADIUS / CANCEL_REACH * depth as f64).ceil() as usize,
    );
    let cancel = |m: &mut Vec<[i64; 2]>,
                  cancelling: bool,
                  far: Option<(usize, &[[f64; 2]], usize)>,
                  pinned_normal: &[bool],
                  budget: &mut Budget|
     -> Option<Vec<[i64; 2]>> {
        if !cancelling {
            return None;
        }
        let before = m.clone();
        flow.cancel(m, depth, depth, far, pinned_normal, &mut || {
            budget.poll(0.0)
        });
        Some(before)
    };
    let free_boundary = vec![false; 2 * n];
    let unpinned = vec![false; n];
    // Round 0 of the rounds below: solve, offsets into cells, jumps read and cancelled.
    let first_round = |start: Vec<f64>, budget: &mut Budget| {
        let mut u = start;
        let m = jumps(&u);
        system.solve(&free_boundary, &m, &mut u, ITERATIONS, &mut |_| {
            budget.poll(0.0)
        });
        into_cells(&mut u, &free_boundary);
        let mut m = jumps(&u);
        let before = cancel(&mut m, true, Some(free), &unpinned, budget);
        (flow.dislocations(&m), u, m, before)
    };
    // The rounds from round `first` on, from offsets `u` and jumps `m` (with `uncancelled`,
    // the jumps before round `first - 1`'s cancellation).
    let rounds = |mut u: Vec<f64>,
                  mut m: Vec<[i64; 2]>,
                  first: usize,
                  mut uncancelled: Option<Vec<[i64; 2]>>,
                  budget: &mut Budget|
     -> (Vec<f64>, Vec<[i64; 2]>) {
        let mut active = vec![false; 2 * n];
        let mut pinned_normal = vec![false; n];
        // Cancelling stops for good once a cancellation strained the lattice too much and
        // `uncancelled`, the jumps as read before it, were taken back (a shell whose rows
        // must really end somewhere, like a dome with rows along its rim).
        let mut cancelling = true;
        for round in first..ROUNDS {
            let share = |within: f64| (round as f64 + within) / ROUNDS as f64;
            if !budget.poll(share(0.0)) {
                break;
            }
            if round == PIN_FROM {
                // From here on the boundary lattice lines sit on the boundary.
                active.copy_from_slice(&fixed);
                for v in 0..n {
                    pinned_normal[v] = fixed[2 * v + 1];
                }
                for k in 0..2 * n {
                    if active[k] {
                        u[k] = 0.0;
                    }
                }
                m = jumps(&u);
                uncancelled = cancel(&mut m, cancelling, None, &pinned_normal, budget);
            }
            let last = round + 1 == ROUNDS;
            let iterations = if last { LAST_ITERATIONS } else { ITERATIONS };
            let u_before = u.clone();
            let mut keep_going = |k: usize| budget.poll(share(k as f64 / iterations as f64));
            system.solve(&active, &m, &mut u, iterations, &mut keep_going);
            if let Some(before) = uncancelled.take() {
                if system.strained(&m, &u) {
                    cancelling = false;
                    m = before;
                    u = u_before;
                    system.solve(&active, &m, &mut u, iterations, &mut keep_going);
                }
            }
            if last {
                break;
            }
            into_cells(&mut u, &active);
            m = jumps(&u);
            let far = (round + 1 < PIN_FROM).then_some(free);
            uncancelled = cancel(&mut m, cancelling, far, &pinned_normal, budget);
        }
        (u, m)
    };
    // The first lattice: integrated at one spacing, or at the scale the surface asks for,
    // whichever keeps fewer dislocations after a first round (see `integrate`).
    let plain = integrate(s, &delta, &transfer, &sp);
    let phi = scale::solve(s, &delta, &transfer, &flow, t, SCALE_LIMIT, &mut |_| {
        budget.poll(0.0)
    });
    let (mut u, mut m) = if phi.iter().any(|&p| p != 0.0) {
        let scaled: Vec<Vector2<f64>> = delta
            .iter()
            .zip(&s.edges)
            .map(|(d, &[a, b])| d * (-(phi[a] + phi[b]) / 2.0).exp())
            .collect();
        let mut at_scale = integrate(s, &scaled, &transfer, &sp);
        for (v, p) in phi.iter().enumerate() {
            at_scale[2 * v] *= p.exp();
            at_scale[2 * v + 1] *= p.exp();
        }
        let plain = first_round(plain, budget);
        let at = first_round(at_scale, budget);
        // One spacing keeps quads of one size, which rigid tiles need (see `integrate`), so
        // the scale must take away at least a fifth of the dislocations.
        let (_, u, m, uncancelled) = if 5 * at.0 < 4 * plain.0 { at } else { plain };
        rounds(u, m, 1, uncancelled, budget)
    } else {
        let m = jumps(&plain);
        rounds(plain, m, 0, None, budget)
    };
    let mut restarted = false;
    if coarse && budget.stopped().is_none() {
        let strained = system.strained_share(&m, &u, STRETCH);
        if strained > STRETCHED {
            if let Some(start) = coarse_start(s, frames, &basis, t, courses, pin, budget) {
                let m2 = jumps(&start);
                let (u2, m2) = rounds(start, m2, 0, None, budget);
                if system.strained_share(&m2, &u2, STRETCH) < strained {
                    (u, m) = (u2, m2);
                    restarted = true;
                }
            }
        }
    }
    let origin = (0..n).map(|v| s.pos[v] + basis[v] * read(&u, v)).collect();
    Lattice {
        origin,
        offset: m,
        pinned,
        coarse_start: restarted,
    }
}

/// Share of the edges stretched by over [`STRETCH`] above which the lattice counts as
/// stretched and is solved again from a coarse start ([`coarse_start`]). A lattice whose
/// rows must end all over a wide part of the surface (rings of a dome of revolution, a bell,
/// an annular vault: the rows at the rim are two or three times as many as at the top; a
/// designer's field along a dome's meridians, whose columns converge on the crown) but whose
/// first lattice ends none there keeps its rows and stretches them: 9-82 % of the edges
/// stretched, quads of up to four target edges and, on the meridians, a hole at the crown.
/// Of the 29 shells of the benchmark sets at most 5.8 % are (a cone, whose rows converge
/// everywhere: its coarse start is worse and not kept), then 4.0 % (a torus patch).
const STRETCHED: f64 = 0.07;

/// Relative edge misfit counted as stretch for [`STRETCHED`]: lower than [`STRAIN`], as a
/// lattice that keeps its rows spreads the shortfall thinly (the meridian field's: 3.6 % of
/// its edges strained by half, 12 % by a third).
const STRETCH: f64 = 0.35;

/// Longest edge of the coarse copy, in target edges.
const COARSE_EDGE: f64 = 2.0;

/// A first lattice for `s` from the lattice solved on a coarser copy of it, as Instant
/// Meshes starts each level from the one above (Jakob et al. 2015, section 5).
///
/// On the working surface (edges under half a target edge) the first lattice is read by
/// rounding each edge's step, and where rows should end all over a wide region, the
/// shortfall is spread so thin that no edge rounds to a new row: the lattice keeps its
/// rows and stretches. On a copy with edges of up to two target edges (shorter along the
/// boundary and the creases, whose vertices simplification keeps) the same shortfall
/// adds up to whole rows on single edges, the rounding ends rows where they should end, and
/// each fine vertex takes the corner of the coarse lattice nearest to it (from the kept
/// vertex nearest to it in steps along the edges). `None` when the copy cannot be made
/// (the working surface is not a valid mesh for simplification, or nothing is simplified)
/// or the budget stopped it.
fn coarse_start(
    s: &Surface,
    frames: &[Vector3<f64>],
    basis: &[Matrix3x2<f64>],
    t: f64,
    courses: Option<&CourseQuads>,
    pin: &[bool],
    budget: &mut Budget,
) -> Option<Vec<f64>> {
    let fine = PolyMesh::new(
        s.pos.iter().map(|&p| Point3::from(p)).collect(),
        s.tris.iter().map(|t| t.to_vec()).collect(),
    )
    .ok()?;
    let (coarse, kept) = simplify_mapped(&fine, COARSE_EDGE * t, &mut || budget.poll(0.0));
    if kept.len() == s.len() || budget.stopped().is_some() {
        return None;
    }
    // Simplification leaves triangles.
    let tris: Vec<[usize; 3]> = coarse
        .faces()
        .iter()
        .map(|f| <[usize; 3]>::try_from(f.as_slice()).ok())
        .collect::<Option<_>>()?;
    let mut copy = Surface::build(
        kept.iter().map(|&v| s.pos[v]).collect(),
        tris,
        Some(kept.iter().map(|&v| s.normals[v]).collect()),
    );
    copy.set_boundary_scale(t * 0.5);
    let copy_frames: Vec<Vector3<f64>> = kept.iter().map(|&v| frames[v]).collect();
    let copy_pin: Vec<bool> = kept.iter().map(|&v| pin[v]).collect();
    let lattice = solve_level(&copy, &copy_frames, t, courses, &copy_pin, budget, false);
    if budget.stopped().is_some() {
        return None;
    }
    let copy_basis = bases(&copy, &copy_frames);
    let copy_sp = spacings(&copy, &copy_basis, t, courses);
    // Each vertex of `s` reads the lattice of the kept vertex nearest to it in steps.
    let mut from = vec![usize::MAX; s.len()];
    let mut queue = VecDeque::new();
    for (c, &v) in kept.iter().enumerate() {
        from[v] = c;
        queue.push_back(v);
    }
    while let Some(a) = queue.pop_front() {
        for &(b, _) in &s.adj[a] {
            if from[b] == usize::MAX {
                from[b] = from[a];
                queue.push_back(b);
            }
        }
    }
    let mut u = vec![0.0; 2 * s.len()];
    for v in 0..s.len() {
        let c = from[v];
        if c == usize::MAX {
            continue;
        }
        let q = lattice.origin[c];
        let k = (copy_basis[c].transpose() * (s.pos[v] - q)).component_div(&copy_sp[c]);
        let corner =
            q + copy_basis[c] * Vector2::new(k.x.round(), k.y.round()).component_mul(&copy_sp[c]);
        let local = basis[v].transpose() * (corner - s.pos[v]);
        u[2 * v] = local.x;
        u[2 * v + 1] = local.y;
    }
    Some(u)
}

/// Per vertex, the lattice's spacing along each axis of its cross frame: `t` both ways, or
/// for level courses ([`CourseQuads`]) `along` on the axis nearer the level and `t` on the
/// one nearer the slope (across the courses). The shorter spacing is blended in by how
/// clearly the vertex has a level ([`LEVEL_SLOPE`]) and how nearly its cross lies along it
/// (`cos^4 2a` of the angle `a` between the level and the nearer axis: 1 along it, 0 at 45
/// degrees), so that where the crosses turn away from the level, or the surface lies flat
/// (a dome's crown), both axes take `t` and neighbours whose nearer axes differ (a cross
/// turning through 45 degrees) agree on their spacings. Each edge's misfit is read with
/// its first end's spacings (the jumps `m` count lattice steps of the end's own size).
fn spacings(
    s: &Surface,
    basis: &[Matrix3x2<f64>],
    t: f64,
    courses: Option<&CourseQuads>,
) -> Vec<Vector2<f64>> {
    let Some(courses) = courses else {
        return vec![Vector2::new(t, t); s.len()];
    };
    let up = Vector3::from(courses.up);
    (0..s.len())
        .map(|v| {
            let n = s.normals[v];
            let slope = up - n * up.dot(&n);
            let sine = slope.norm();
            let (c0, c1) = (
                basis[v].column(0).dot(&slope).abs(),
                basis[v].column(1).dot(&slope).abs(),
            );
            let along_level = if sine > 0.0 {
                ((c0 * c0 - c1 * c1).abs() / (sine * sine)).powi(4)
            } else {
                0.0
            };
            let share = (sine / LEVEL_SLOPE.to_radians().sin()).min(1.0) * along_level;
            let along = t - (t - courses.along) * share;
            // The axis nearer the slope runs across the courses.
            if c0 > c1 {
                Vector2::new(t, along)
            } else {
                Vector2::new(along, t)
            }
        })
        .collect()
}

/// Slope (degrees from level) from which a vertex has a level clearly enough for the
/// courses' spacing along it ([`spacings`]); below it the spacing fades to `t` (the crown
/// of a dome, a floor), as the laying order counts tiles on slopes from 20 degrees
/// ([`crate::tiles::SLOPE_DEGREES`]).
const LEVEL_SLOPE: f64 = crate::tiles::SLOPE_DEGREES;

/// Relative edge misfit counted as strain.
const STRAIN: f64 = 0.5;

/// Fraction of strained edges above which a cancellation round is undone.
const STRAINED_FRACTION: f64 = 0.05;

/// The least-squares lattice energy of one level.
struct System<'a> {
    s: &'a Surface,
    transfer: &'a [Matrix2<f64>],
    delta: &'a [Vector2<f64>],
    /// Per edge weight of its misfit (see [`edge_weights`]).
    weight: &'a [f64],
    /// Per vertex, the lattice spacing along each axis of its frame.
    sp: &'a [Vector2<f64>],
}

impl System<'_> {
    /// True when more than [`STRAINED_FRACTION`] of the edges disagree with their lattice
    /// step by over [`STRAIN`] of their length.
    fn strained(&self, m: &[[i64; 2]], u: &[f64]) -> bool {
        self.strained_share(m, u, STRAIN) > STRAINED_FRACTION
    }

    /// Share of the edges that disagree with their lattice step by over `strain` of their
    /// length.
    fn strained_share(&self, m: &[[i64; 2]], u: &[f64], strain: f64) -> f64 {
        let count = self
            .s
            .edges
            .iter()
            .enumerate()
            .filter(|&(e, &[a, b])| {
                let ua = Vector2::new(u[2 * a], u[2 * a + 1]);
                let ub = Vector2::new(u[2 * b], u[2 * b + 1]);
                let r = self.delta[e] + self.transfer[e] * ub
                    - ua
                    - Vector2::new(m[e][0] as f64, m[e][1] as f64).component_mul(&self.sp[a]);
                r.norm() > strain * self.delta[e].norm()
            })
            .count();
        count as f64 / self.s.edges.len().max(1) as f64
    }

    /// Minimises the energy over the offsets `u` for fixed jumps `m`, with the components
    /// flagged in `active` held at zero.
    fn solve(
        &self,
        active: &[bool],
        m: &[[i64; 2]],
        u: &mut [f64],
        iterations: usize,
        keep_going: &mut dyn FnMut(usize) -> bool,
    ) {
        // Held components of every vector the solver applies the operator to are exactly
        // zero (they start at zero, and the operator keeps them there), so the edge loop
        // needs no masking. Edges are packed (u32 ends, transfer matrix, weight) for speed.
        debug_assert!(active.iter().zip(u.iter()).all(|(&a, &x)| !a || x == 0.0));
        let packed: Vec<([u32; 2], [f64; 4], f64)> = self
            .s
            .edges
            .iter()
            .zip(self.transfer)
            .zip(self.weight)
            .map(|((&[a, b], t), &w)| {
                (
                    [a as u32, b as u32],
                    [t[(0, 0)], t[(0, 1)], t[(1, 0)], t[(1, 1)]],
                    w,
                )
            })
            .collect();
        let scatter = Scatter::default();
        let apply = |x: &[f64], out: &mut [f64]| {
            out.iter_mut().zip(x).for_each(|(o, x)| *o = 1e-6 * x);
            scatter.add(packed.len(), out, |range, out| {
                for &([a, b], t, w) in &packed[range] {
                    let (a, b) = (a as usize, b as usize);
                    let (xa0, xa1) = (x[2 * a], x[2 * a + 1]);
                    let (xb0, xb1) = (x[2 * b], x[2 * b + 1]);
                    let l0 = w * (t[0] * xb0 + t[1] * xb1 - xa0);
                    let l1 = w * (t[2] * xb0 + t[3] * xb1 - xa1);
                    out[2 * a] -= l0;
                    out[2 * a + 1] -= l1;
                    out[2 * b] += t[0] * l0 + t[2] * l1;
                    out[2 * b + 1] += t[1] * l0 + t[3] * l1;
                }
            });
            for k in 0..out.len() {
                if active[k] {
                    out[k] = x[k];
                }
            }
        };
        let mut rhs: Vec<f64> = u.iter().map(|x| 1e-6 * x).collect();
        for (e, &[a, b]) in self.s.edges.iter().enumerate() {
            let c = (self.delta[e]
                - Vector2::new(m[e][0] as f64, m[e][1] as f64).component_mul(&self.sp[a]))
                * self.weight[e];
            let cb = self.transfer[e].transpose() * c;
            rhs[2 * a] += c.x;
            rhs[2 * a + 1] += c.y;
            rhs[2 * b] -= cb.x;
            rhs[2 * b + 1] -= cb.y;
        }
        for k in 0..rhs.len() {
            if active[k] {
                rhs[k] = 0.0;
            }
        }
        conjugate_gradient(apply, &rhs, u, iterations, 1e-6, None, keep_going);
    }
}

/// Per edge: the cotangent weight of the edge (half the cotangents of the opposite angles),
/// relative to that of an equilateral mesh and clamped to `[0.1, 4]`. With equal weights the
/// least-squares lattice is that of a graph, which on a skewed or anisotropic triangulation
/// (a bilinear grid over a tapering patch, slivers) is not the surface's: the lattice then
/// shears and stretches. Cotangent weights make it the surface's.
fn edge_weights(s: &Surface) -> Vec<f64> {
    let mut weight = vec![0.0; s.edges.len()];
    for &[a, b, c] in &s.tris {
        for (p, q, r) in [(a, b, c), (b, c, a), (c, a, b)] {
            let (u, v) = (s.pos[p] - s.pos[r], s.pos[q] - s.pos[r]);
            let cross = u.cross(&v).norm();
            if cross > 1e-300 {
                weight[s.edge(p, q)] += 0.5 * u.dot(&v) / cross;
            }
        }
    }
    let equilateral = 1.0 / 3f64.sqrt();
    weight
        .iter()
        .map(|w| (w / equilateral).clamp(0.1, 4.0))
        .collect()
}

/// Initial lattice by integration along a breadth-first tree from vertex 0: each vertex takes
/// the corner of its parent's lattice nearest to it, from the edge vectors `delta` in the
/// frames (see [`scale::step`]). This fixes the integer structure everywhere at once (a
/// least-squares solve from zero would collapse every lattice onto one point); the solves
/// then relax it.
///
/// The solve also integrates once with edge vectors scaled by the surface's conformal scale
/// ([`scale`]; the offsets are then multiplied back to lengths) and keeps that first lattice
/// when, after a first round, it has at least a fifth fewer dislocations. Integrated at one
/// spacing, the tree carries the misclosure of every triangle it crosses and leaves
/// dislocations where its fronts meet that no later round moves, far apart and far from the
/// boundary (an evenly triangulated vault: 34 where its triangulation in rows gets 2;
/// README, *Remesher*); at the scale they come out fewer and in pairs the first cancellation
/// removes. The rounds always solve at one spacing: quads keep one size wherever the rows
/// allow, which rigid tiles need (a lattice kept at the scale left the 3 m dome's greedy
/// tiling with 147 tiles cut to fit against 98), and where the scale gains little (a fifth)
/// the lattice of one spacing is kept for the same reason.
fn integrate(
    s: &Surface,
    delta: &[Vector2<f64>],
    transfer: &[Matrix2<f64>],
    sp: &[Vector2<f64>],
) -> Vec<f64> {
    let n = s.len();
    let mut u = vec![0.0; 2 * n];
    let mut done = vec![false; n];
    // Maps coordinates in `x`'s frame into `y`'s (the ends of an edge).
    let into = |x: usize, y: usize| -> Matrix2<f64> {
        let e = s.edge(x, y);
        if x < y {
            transfer[e].transpose()
        } else {
            transfer[e]
        }
    };
    for seed in 0..n {
        if done[seed] {
            continue;
        }
        done[seed] = true;
        let mut queue = std::collections::VecDeque::from([seed]);
        while let Some(a) = queue.pop_front() {
            let ua = Vector2::new(u[2 * a], u[2 * a + 1]);
            for &(b, _) in &s.adj[a] {
                if done[b] {
                    continue;
                }
                // In a's frame: b seen from a's corner, the corner of a's lattice nearest to
                // b, then that corner seen from b, carried into b's frame.
                let d = scale::step(s, delta, transfer, a, b);
                let local = (d - ua).component_div(&sp[a]);
                let corner =
                    ua + Vector2::new(local.x.round(), local.y.round()).component_mul(&sp[a]);
                let ub = into(a, b) * (corner - d);
                u[2 * b] = ub.x;
                u[2 * b + 1] = ub.y;
                done[b] = true;
                queue.push_back(b);
            }
        }
    }
    u
}

/// Per triangle, the sum of the lattice steps the surface and the field ask for around it
/// (the edge vectors at full length, carried into the frame of the triangle's first vertex
/// by the frame transfers), in quad lengths: the continuous dislocation density the integer
/// curls should add up to over a patch. It is zero on a developable surface with a parallel
/// field, and grows with Gaussian curvature and with the field's turning (a bend, a guide
/// at an angle to the designer's field).
fn burgers_density(
    s: &Surface,
    delta: &[Vector2<f64>],
    transfer: &[Matrix2<f64>],
    t: f64,
) -> Vec<[f64; 2]> {
    s.tris
        .iter()
        .map(|&tri| {
            let [ab, bc, ca] = scale::steps_around(s, delta, transfer, tri);
            let sum = ab + bc + ca;
            [sum.x / t, sum.y / t]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::surface::samples::sheet;

    /// The Burgers density summed over a flat 2 x 2 patch of spacing 0.1, with crosses turned
    /// by `turn * x` radians at `x`, in quad lengths of 0.1.
    fn patch_density(turn: f64) -> [f64; 2] {
        let s = sheet(20, 0.1, (0..0, 0..0), |_, _| 0.0);
        let frames: Vec<Vector3<f64>> = s
            .pos
            .iter()
            .map(|p| Vector3::new((turn * p.x).cos(), (turn * p.x).sin(), 0.0))
            .collect();
        let (transfer, delta) = edge_frames(&s, &bases(&s, &frames));
        burgers_density(&s, &delta, &transfer, 0.1)
            .iter()
            .fold([0.0; 2], |acc, d| [acc[0] + d[0], acc[1] + d[1]])
    }

    #[test]
    fn the_density_is_nil_for_parallel_crosses_and_grows_with_their_turning() {
        let still = patch_density(0.0);
        assert!(still[0].hypot(still[1]) < 1e-9, "{still:?}");
        let slow = patch_density(0.05);
        let fast = patch_density(0.1);
        // Crosses turning by `turn` radians per metre along x bend the rows along x: over the
        // patch's 2 m height the rows on one side are `2 turn` longer per metre than on the
        // other, so rows of 0.1 m must gain `turn * 2 * 2 / 0.1` columns (2 at 0.05, 4 at
        // 0.1), a Burgers content along the rows (x), not across them. Read in each step's
        // start frame, it came out twice as long and across the rows ([0.8, 7.9] at 0.1).
        for (d, turn) in [(slow, 0.05), (fast, 0.1)] {
            let expected = turn * 2.0 * 2.0 / 0.1;
            assert!((d[0] / expected - 1.0).abs() < 0.02, "{d:?} at {turn}");
            assert!(d[1].abs() < 0.15 * d[0], "{d:?} at {turn}");
        }
    }
}
