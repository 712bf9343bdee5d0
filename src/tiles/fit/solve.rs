//! The least-squares placement of the fit stage: every tile a rigid body on the surface
//! (a tangent step `u, v` and a turn `phi` about its normal), joints pulled towards the
//! nominal width, by Levenberg-Marquardt steps whose linear systems are solved by
//! conjugate gradients with a block-Jacobi preconditioner.
//!
//! Residuals, each with its gradient over the (at most two) tiles it involves:
//! - **joints**: for every [`Contact`], the distance from each end of either facing side to
//!   the other tile's side plane (at the bottom or the top, whichever is closer), minus the
//!   joint;
//!   an overlap (negative distance) counts `overlap_slope` times as much per unit, so the
//!   stage would rather open a joint than press two tiles into each other; a gap wider
//!   than the joint by more than `wide` costs only linearly beyond that, and by more than
//!   `tear` only logarithmically ([`capped`]);
//! - **bond**: for two full tiles side by side (a bed joint), the offset of their centres
//!   along the joint, where it leaves the band the bond allows ([`BondBand`]);
//! - **edge**: a tile that started over the surface may not move its origin more than a
//!   quarter of its width beyond the surface's edge (an outer course that does not fit
//!   overhangs and is cut, it is not pushed off);
//! - **anchors**: a weak pull of each tile towards where the section 3.5 placement put it,
//!   which only fixes what the joints leave free (sliding the whole layout).

use nalgebra::{Matrix3, Vector3};

use super::contacts::{Contact, Side};
use crate::geom::SurfaceIndex;
use crate::parallel;
use crate::tiles::Frame;

/// Where the centre offset along a bed joint may lie: `nominal +- tolerance`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BondBand {
    /// Offset of the second tile's centre from the first's along the first's side.
    pub nominal: f64,
    /// Allowed deviation either way.
    pub tolerance: f64,
}

/// The weights of the residuals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Weights {
    /// Slope of the joint residual where the tiles overlap, relative to 1 where the joint
    /// is wider than the nominal one.
    pub overlap_slope: f64,
    /// Slope of the joint residual where the joint is open but narrower than the nominal
    /// one ([`Problem::joint_residual`]).
    pub narrow_slope: f64,
    /// Weight of the bond residual.
    pub bond: f64,
    /// Weight of the anchor residuals.
    pub anchor: f64,
    /// Weight per unit of a tile's origin moving beyond the surface's edge.
    pub edge: f64,
    /// How much wider than the joint a gap may be before its cost grows only linearly
    /// ([`capped`]); zero keeps every joint's cost quadratic.
    pub wide: f64,
    /// How much wider than the joint a gap may be before its cost grows only
    /// logarithmically, a tear rather than a joint ([`capped`]); at least `wide`, infinite
    /// to keep Huber's loss beyond `wide`.
    pub tear: f64,
}

/// A joint residual `excess` (with its slope) past `wide` and `tear`, as the square root of
/// a loss `rho` with `rho(e) = e^2` up to `wide`:
/// - beyond `wide` the loss grows linearly, `2 wide e - wide^2` (Huber's loss), so that a
///   gap that is no joint any more (where courses part, at a singularity, beside a course
///   that ends) pulls its tiles with a bounded force instead of one growing with the gap;
///   quadratic it spreads the misfit it cannot close over the joints around it and presses
///   tiles on its other side into overlaps, which are then cut;
/// - beyond `tear` it grows with the logarithm, `rho(tear) + 2 wide tear ln(e / tear)`
///   (value and slope continuous), so that two gaps cost more than one as wide as both:
///   where a course's joints cannot all close (quads wider than the tiles where courses
///   fan out or converge, around singularities), the misfit gathers into a few tears, which
///   the finishing fills with pieces cut to the room ([`crate::tiles`]' tear fill), and the
///   joints beside them close, instead of every joint opening a little. A mason does the
///   same: joints at the nominal width, the leftover in one cut piece.
///
/// Overlaps (negative excess) keep their full, steep cost.
fn capped(excess: f64, slope: f64, wide: f64, tear: f64) -> (f64, f64) {
    if wide <= 0.0 || excess <= wide {
        return (excess, slope);
    }
    // Below `wide` the logarithm's branch would not meet Huber's (nor stay real).
    let tear = tear.max(wide);
    let huber = |e: f64| 2.0 * wide * e - wide * wide;
    if excess > tear {
        let r = (huber(tear) + 2.0 * wide * tear * (excess / tear).ln()).sqrt();
        (r, slope * wide * tear / (excess * r))
    } else {
        let r = huber(excess).sqrt();
        (r, slope * wide / r)
    }
}

/// The placement problem.
pub(crate) struct Problem<'a> {
    /// Box sizes per tile.
    pub sizes: &'a [[f64; 3]],
    /// Facing sides.
    pub contacts: &'a [Contact],
    /// Per contact, the band of a bed joint between full tiles.
    pub bands: &'a [Option<BondBand>],
    /// Frames of the starting placement.
    pub anchors: &'a [Frame],
    /// How far beyond the surface's edge each starting placement lies (tiles a ragged quad
    /// mesh puts there may stay there, no further out).
    pub beyond_start: &'a [Vector3<f64>],
    /// Nominal joint.
    pub joint: f64,
    /// Residual weights.
    pub weights: Weights,
    /// The surface the tiles stay on.
    pub surface: &'a SurfaceIndex,
    /// Per contact (missing ones: `false`), whether its joint is being closed: its cost stays
    /// quadratic however wide the gap, not [`capped`], so that a tear too narrow for a piece
    /// pulls its tiles together ([`super::close`]).
    pub closing: &'a [bool],
}

/// A residual's gradient on one tile: the step `u` (along `x`), `v` (along `y`), `phi`.
type Grad = Vector3<f64>;

/// The normal equations of one linearisation: `H` in 3 x 3 blocks (one on the diagonal per
/// tile, one per contact) and the gradient `g`.
struct Normal {
    diag: Vec<Matrix3<f64>>,
    off: Vec<Matrix3<f64>>,
    g: Vec<Vector3<f64>>,
    value: f64,
}

/// How a point attached to tile `frame` moves with its step: columns `u`, `v`, `phi`.
fn point_motion(frame: &Frame, p: &Vector3<f64>) -> [Vector3<f64>; 3] {
    [frame.x, frame.y, frame.z.cross(&(p - frame.origin.coords))]
}

/// Signed distance `m . (p - c)` from point `p` of one tile to the side plane `(m, c)` of
/// another, with its gradients on the point's tile and on the plane's tile.
fn plane_distance(
    point_tile: &Frame,
    p: &Vector3<f64>,
    plane_tile: &Frame,
    m: &Vector3<f64>,
    c: &Vector3<f64>,
) -> (f64, Grad, Grad) {
    let d = m.dot(&(p - c));
    let [px, py, pr] = point_motion(point_tile, p);
    let [cx, cy, cr] = point_motion(plane_tile, c);
    let on_point = Vector3::new(m.dot(&px), m.dot(&py), m.dot(&pr));
    let turn = plane_tile.z.cross(m).dot(&(p - c)) - m.dot(&cr);
    let on_plane = Vector3::new(-m.dot(&cx), -m.dot(&cy), turn);
    (d, on_point, on_plane)
}

/// A side of a tile placed by `frame`: outward normal, centre, direction along it, half
/// length.
pub(super) fn side_line(
    frame: &Frame,
    size: &[f64; 3],
    side: Side,
) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>, f64) {
    let m = side.normal(frame);
    let (reach, half) = side.extents(size);
    (m, frame.origin.coords + m * reach, frame.z.cross(&m), half)
}

impl Problem<'_> {
    /// The residual of one joint measure `d` (a corner's distance to the other tile's side)
    /// and its slope: `d - joint` where the joint is wider than the nominal one, with the
    /// slope `narrow_slope` where it is narrower and `overlap_slope` where the tiles overlap
    /// (continuous, piecewise linear), then [`capped`] where it is far too wide.
    ///
    /// A narrower joint costs more than a wider one because the mortar fills a wide joint but
    /// cannot be pressed below the joint, and because of the joints' shape: two tiles turned
    /// against each other in the surface's plane (where a course bends, around a
    /// singularity) leave a wedge-shaped joint, `delta` wider at one end than at the other.
    /// With equal slopes the least-squares placement centres the wedge on the joint and its
    /// narrow end, which is what the outline measure (and the mason) sees, lies `delta / 2`
    /// under it; with slope `s` on the narrow side it lies `delta / (1 + s^2)` under it.
    fn joint_residual(&self, d: f64, closing: bool) -> (f64, f64) {
        let (j, k, s) = (
            self.joint,
            self.weights.overlap_slope,
            self.weights.narrow_slope,
        );
        let (raw, slope) = if d >= j {
            (d - j, 1.0)
        } else if d >= 0.0 {
            (s * (d - j), s)
        } else {
            (k * d - s * j, k)
        };
        if closing {
            return (raw, slope);
        }
        capped(raw, slope, self.weights.wide, self.weights.tear)
    }

    /// Calls `row(tile_a, grad_a, tile_b, grad_b, value)` for every residual at `frames`
    /// (`tile_b` is `usize::MAX` for a residual of one tile), contact residuals first, in
    /// contact order, with the contact's index.
    fn residuals(
        &self,
        frames: &[Frame],
        beyond: &[Vector3<f64>],
        mut row: impl FnMut(Option<usize>, usize, Grad, usize, Grad, f64),
    ) {
        for (ci, c) in self.contacts.iter().enumerate() {
            let [a, b] = c.tiles;
            let closing = self.closing.get(ci).copied().unwrap_or(false);
            let (fa, fb) = (&frames[a], &frames[b]);
            let (ma, ca, ta, la) = side_line(fa, &self.sizes[a], c.sides[0]);
            let (mb, cb, tb, lb) = side_line(fb, &self.sizes[b], c.sides[1]);
            // Each corner of either facing side against the other tile's side plane (the
            // separating-axis measure of the report): all four always count, so that no tile
            // can shed a joint it cannot fit by sliding away from its neighbour.
            for (point_tile, fp, t_own, c_own, l_own, plane_tile, fq, m_other, c_other) in [
                (a, fa, ta, ca, la, b, fb, mb, cb),
                (b, fb, tb, cb, lb, a, fa, ma, ca),
            ] {
                // At each end the bottom or the top corner, whichever is closer: on a convex
                // surface the bottoms close the joint, on a concave one the tops.
                for sign in [-1.0, 1.0] {
                    let bottom = c_own + t_own * (sign * l_own);
                    let top = bottom + fp.z * self.sizes[point_tile][2];
                    let (db, gpb, gqb) = plane_distance(fp, &bottom, fq, &m_other, &c_other);
                    let (dt, gpt, gqt) = plane_distance(fp, &top, fq, &m_other, &c_other);
                    let (d, g_point, g_plane) = if dt < db {
                        (dt, gpt, gqt)
                    } else {
                        (db, gpb, gqb)
                    };
                    let (excess, slope) = self.joint_residual(d, closing);
                    row(
                        Some(ci),
                        point_tile,
                        g_point * slope,
                        plane_tile,
                        g_plane * slope,
                        excess,
                    );
                }
            }
            if let Some(band) = self.bands[ci] {
                let offset = ta.dot(&(fb.origin - fa.origin));
                let (low, high) = (band.nominal - band.tolerance, band.nominal + band.tolerance);
                let excess = offset - offset.clamp(low, high);
                if excess != 0.0 {
                    let w = self.weights.bond;
                    let on_b = Vector3::new(ta.dot(&fb.x), ta.dot(&fb.y), 0.0) * w;
                    let on_a = Vector3::new(
                        -ta.dot(&fa.x),
                        -ta.dot(&fa.y),
                        fa.z.cross(&ta).dot(&(fb.origin - fa.origin)),
                    ) * w;
                    row(Some(ci), a, on_a, b, on_b, w * excess);
                }
            }
        }
        // An outer course may overhang the surface's edge, but no tile that the section 3.5
        // placement put on the surface may be pushed off it: its origin stays within a quarter
        // of its width beyond the edge (or where it started, if further), so that what is
        // left on the surface after cutting is still more than a sliver.
        for (t, (frame, out)) in frames.iter().zip(beyond).enumerate() {
            let start = self
                .beyond_start
                .get(t)
                .map_or(0.0, |b| b.norm())
                .max(self.sizes[t][1] / 4.0);
            let excess = out.norm() - start;
            if excess > 0.0 {
                let away = out / out.norm();
                let w = self.weights.edge;
                row(
                    None,
                    t,
                    Vector3::new(away.dot(&frame.x), away.dot(&frame.y), 0.0) * w,
                    usize::MAX,
                    Grad::zeros(),
                    w * excess,
                );
            }
        }
        let w = self.weights.anchor;
        for (t, (frame, anchor)) in frames.iter().zip(self.anchors).enumerate() {
            let moved = frame.origin - anchor.origin;
            let lever = self.sizes[t][0] / 2.0;
            let turn = anchor
                .x
                .cross(&frame.x)
                .dot(&frame.z)
                .atan2(anchor.x.dot(&frame.x));
            row(
                None,
                t,
                Vector3::new(w, 0.0, 0.0),
                usize::MAX,
                Grad::zeros(),
                w * moved.dot(&frame.x),
            );
            row(
                None,
                t,
                Vector3::new(0.0, w, 0.0),
                usize::MAX,
                Grad::zeros(),
                w * moved.dot(&frame.y),
            );
            row(
                None,
                t,
                Vector3::new(0.0, 0.0, w * lever),
                usize::MAX,
                Grad::zeros(),
                w * lever * turn,
            );
        }
    }

    /// The sum of squared residuals at `frames`, wherever their origins lie.
    pub fn objective(&self, frames: &[Frame]) -> f64 {
        self.value(frames, &beyond_edge(self.surface, frames))
    }

    /// The sum of squared residuals at `frames`, whose origins lie `beyond` the surface's
    /// edge by these offsets.
    pub fn value(&self, frames: &[Frame], beyond: &[Vector3<f64>]) -> f64 {
        let mut value = 0.0;
        self.residuals(frames, beyond, |_, _, _, _, _, r| value += r * r);
        value
    }

    fn normal_equations(&self, frames: &[Frame], beyond: &[Vector3<f64>]) -> Normal {
        let n = frames.len();
        let mut eq = Normal {
            diag: vec![Matrix3::zeros(); n],
            off: vec![Matrix3::zeros(); self.contacts.len()],
            g: vec![Vector3::zeros(); n],
            value: 0.0,
        };
        self.residuals(frames, beyond, |contact, a, ga, b, gb, r| {
            eq.value += r * r;
            eq.diag[a] += ga * ga.transpose();
            eq.g[a] += ga * r;
            if b != usize::MAX {
                eq.diag[b] += gb * gb.transpose();
                eq.g[b] += gb * r;
                let c = contact.expect("two-tile residuals belong to a contact");
                // Blocks are stored as (first tile of the contact, second tile).
                if a == self.contacts[c].tiles[0] {
                    eq.off[c] += ga * gb.transpose();
                } else {
                    eq.off[c] += gb * ga.transpose();
                }
            }
        });
        eq
    }
}

/// `y = (H + damping) x` for the block matrix of `eq`.
fn multiply(
    eq: &Normal,
    damped: &[Matrix3<f64>],
    contacts: &[Contact],
    x: &[Vector3<f64>],
    y: &mut [Vector3<f64>],
) {
    for (t, out) in y.iter_mut().enumerate() {
        *out = damped[t] * x[t];
    }
    for (c, block) in contacts.iter().zip(&eq.off) {
        let [a, b] = c.tiles;
        y[a] += block * x[b];
        y[b] += block.transpose() * x[a];
    }
}

fn dot(a: &[Vector3<f64>], b: &[Vector3<f64>]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x.dot(y)).sum()
}

/// What one run of [`Problem::solve`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Progress {
    /// Steps taken (accepted or not).
    pub iterations: usize,
    /// Whether the last steps no longer lowered the objective noticeably.
    pub converged: bool,
    /// Whether `keep_going` asked to stop.
    pub stopped: bool,
    /// Objective at the start and at the end.
    pub start: f64,
    /// Objective at the end.
    pub end: f64,
}

impl Problem<'_> {
    /// Levenberg-Marquardt from `frames` (changed in place) for at most `max_iterations`
    /// steps, asking `keep_going(fraction of iterations done)` between conjugate-gradient
    /// rounds; returns as soon as it answers `false`, with the best placement so far.
    pub fn solve(
        &self,
        frames: &mut [Frame],
        max_iterations: usize,
        keep_going: &mut dyn FnMut(f64) -> bool,
    ) -> Progress {
        let n = frames.len();
        let mut beyond = beyond_edge(self.surface, frames);
        let start = self.value(frames, &beyond);
        let mut progress = Progress {
            iterations: 0,
            converged: false,
            stopped: false,
            start,
            end: start,
        };
        let mut mu = 1e-4;
        let mut kept: Option<Normal> = None;
        let mut current = start;
        let mut calm = 0;
        while progress.iterations < max_iterations {
            progress.iterations += 1;
            // After a rejected step the frames are back where they were: the same equations.
            let eq = match kept.take() {
                Some(eq) => eq,
                None => self.normal_equations(frames, &beyond),
            };
            current = eq.value;
            let damped: Vec<Matrix3<f64>> = eq
                .diag
                .iter()
                .map(|d| {
                    d + Matrix3::from_diagonal(&d.diagonal()) * mu + Matrix3::identity() * 1e-12
                })
                .collect();
            let inverse: Vec<Matrix3<f64>> = damped
                .iter()
                .map(|d| d.try_inverse().unwrap_or_else(Matrix3::identity))
                .collect();
            // Conjugate gradients on (H + damping) step = -g.
            let mut step = vec![Vector3::zeros(); n];
            let mut r: Vec<Vector3<f64>> = eq.g.iter().map(|g| -g).collect();
            let mut z: Vec<Vector3<f64>> = r.iter().zip(&inverse).map(|(r, m)| m * r).collect();
            let mut p = z.clone();
            let mut rz = dot(&r, &z);
            let target = rz.abs() * CG_REDUCTION;
            let mut ap = vec![Vector3::zeros(); n];
            for round in 0..CG_ROUNDS {
                if rz.abs() <= target {
                    break;
                }
                if round % 32 == 31
                    && !keep_going(progress.iterations as f64 / max_iterations as f64)
                {
                    progress.stopped = true;
                    break;
                }
                multiply(&eq, &damped, self.contacts, &p, &mut ap);
                let pap = dot(&p, &ap);
                if pap <= 0.0 {
                    break;
                }
                let alpha = rz / pap;
                for t in 0..n {
                    step[t] += p[t] * alpha;
                    r[t] -= ap[t] * alpha;
                    z[t] = inverse[t] * r[t];
                }
                let next = dot(&r, &z);
                let beta = next / rz;
                rz = next;
                for t in 0..n {
                    p[t] = z[t] + p[t] * beta;
                }
            }
            if progress.stopped {
                break;
            }
            let before: Vec<Frame> = frames.to_vec();
            let before_beyond = beyond.clone();
            // Each tile is put back on the surface on its own (a closest-point query each):
            // on the threads of `parallel`, the same result however they split the tiles.
            parallel::each_mut2(frames, &mut beyond, |t, frame, beyond| {
                (*frame, *beyond) = self.moved(frame, &clamped(&step[t], &self.sizes[t]));
            });
            let value = self.value(frames, &beyond);
            if value < current {
                calm = if current - value < CALM * current.max(1e-300) {
                    calm + 1
                } else {
                    0
                };
                current = value;
                mu = (mu / 3.0).max(1e-9);
                if calm >= 2 {
                    progress.converged = true;
                    break;
                }
            } else {
                frames.copy_from_slice(&before);
                beyond.copy_from_slice(&before_beyond);
                kept = Some(eq);
                mu *= 8.0;
                if mu > 1e6 {
                    progress.converged = true;
                    break;
                }
            }
            if !keep_going(progress.iterations as f64 / max_iterations as f64) {
                progress.stopped = true;
                break;
            }
        }
        progress.end = current.min(self.value(frames, &beyond));
        progress
    }

    /// `frame` after the step `(u, v, phi)`, put back on the surface (see [`place`]), and
    /// how far beyond the surface's edge its origin now lies.
    pub(super) fn moved(&self, frame: &Frame, step: &Vector3<f64>) -> (Frame, Vector3<f64>) {
        let origin = frame.origin.coords + frame.x * step.x + frame.y * step.y;
        let (s, c) = step.z.sin_cos();
        let x = frame.x * c + frame.y * s;
        place(self.surface, &origin, &x, &frame.z)
    }
}

/// How far beyond the surface's edge each of `frames` lies (see [`place`]).
fn beyond_edge(surface: &SurfaceIndex, frames: &[Frame]) -> Vec<Vector3<f64>> {
    frames
        .iter()
        .map(|f| place(surface, &f.origin.coords, &f.x, &f.z).1)
        .collect()
}

/// A frame with its origin at the surface point closest to `origin`, `z` the surface normal
/// there (turned to agree with `up`), and `x` the direction `along` laid into that plane;
/// and the offset (in the tangent plane at the edge) of the origin beyond the surface's
/// edge, zero over the surface. Beyond the edge the surface is continued by its tangent
/// plane there, so that tiles of the outer courses can move out past it (they are cut to it
/// later).
pub(crate) fn place(
    surface: &SurfaceIndex,
    origin: &Vector3<f64>,
    along: &Vector3<f64>,
    up: &Vector3<f64>,
) -> (Frame, Vector3<f64>) {
    let (point, mut z, beyond) = match surface.closest(origin) {
        // Beyond the edge the offset to the closest point runs along the surface, not across.
        Some(sp) if sp.on_boundary || beside(&(origin - sp.point), &sp.face_normal) => {
            let off = origin - sp.point;
            let along_surface = off - sp.normal * sp.normal.dot(&off);
            (sp.point + along_surface, sp.normal, along_surface)
        }
        Some(sp) => (sp.point, sp.normal, Vector3::zeros()),
        None => (*origin, *up, Vector3::zeros()),
    };
    if z.dot(up) < 0.0 {
        z = -z;
    }
    (Frame::from_normal(point.into(), z, along), beyond)
}

/// `step` held within a trust region: a tile moves at most its width and turns at most
/// [`MAX_TURN`] per step, where the linearisation still roughly holds; a longer step is
/// shortened along its own direction. (A quarter of the width made little difference on the
/// 3 m spherical cap, where tiles move furthest: p95 28.4 -> 26.5 mm, cuts 52 -> 55.)
fn clamped(step: &Vector3<f64>, size: &[f64; 3]) -> Vector3<f64> {
    let reach = size[1];
    let scale = (reach / step.xy().norm().max(1e-300))
        .min(MAX_TURN / step.z.abs().max(1e-300))
        .min(1.0);
    step * scale
}

/// Largest turn of a tile in one step, radians.
const MAX_TURN: f64 = 0.2;

/// Whether `offset` (from the closest surface point to a point) runs more along the surface
/// than across it: over the surface it is along the normal (within the small normal cone of
/// a fine mesh's edges and corners); beyond the surface's edge it runs sideways.
fn beside(offset: &Vector3<f64>, normal: &Vector3<f64>) -> bool {
    let across = normal.dot(offset).abs();
    (offset - normal * normal.dot(offset)).norm() > across.max(1e-12)
}

/// A step that lowers the objective by less than this share of it is calm; two calm steps
/// in a row end the fit (converged).
const CALM: f64 = 1e-3;

/// Conjugate gradients stop once the preconditioned residual has fallen to this share of
/// its start (the squared norm to 1e-4): each step only needs to point the right way, the
/// next step corrects it.
const CG_REDUCTION: f64 = 1e-4;

/// Most conjugate-gradient rounds per step.
const CG_ROUNDS: usize = 250;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Topology, generate};
    use crate::tiles::fit::contacts;
    use crate::tiles::{TileSpec, build};

    /// A staggered 6 x 4 grid of unit quads with tiles jittered off their places.
    fn setup() -> (Vec<[f64; 3]>, Vec<Contact>, Vec<Frame>, SurfaceIndex) {
        let mesh = generate::grid(6, 4);
        let pattern =
            crate::pattern::solve(&mesh, &crate::pattern::PatternOptions::default()).unwrap();
        let spec = TileSpec {
            length: 1.9,
            width: 0.95,
            thickness: 0.1,
            joint: 0.1,
        };
        let tiles = build(&mesh, &pattern, &spec).unwrap();
        let topology = Topology::new(&mesh).unwrap();
        let found = contacts::contacts(&mesh, &topology, &tiles);
        let surface = SurfaceIndex::from_polymesh(&generate::grid(12, 8));
        let frames: Vec<Frame> = tiles
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let k = i as f64;
                let mut f = t.frame;
                f.origin += Vector3::new(0.03 * (k * 1.7).sin(), 0.04 * (k * 2.3).cos(), 0.0);
                let a: f64 = 0.05 * (k * 0.9).sin();
                let x = f.x * a.cos() + f.y * a.sin();
                place(&surface, &f.origin.coords, &x, &f.z).0
            })
            .collect();
        (
            tiles.iter().map(|t| t.size).collect(),
            found,
            frames,
            surface,
        )
    }

    #[test]
    fn a_joint_cost_gathers_what_cannot_close_into_tears() {
        let (wide, tear) = (0.01, 0.015);
        let rho = |e: f64| capped(e, 1.0, wide, tear).0.powi(2);
        // Quadratic, then Huber's, then the logarithm, each slope continuous with the last.
        for e in [-0.004, 0.003, 0.008, 0.012, 0.02, 0.05, 0.2] {
            let (r, slope) = capped(e, 1.0, wide, tear);
            let h = 1e-7;
            let numeric =
                (capped(e + h, 1.0, wide, tear).0 - capped(e - h, 1.0, wide, tear).0) / (2.0 * h);
            assert!(
                (numeric - slope).abs() < 1e-5 * (1.0 + slope.abs()),
                "at {e}"
            );
            assert!(r.is_finite());
        }
        for at in [wide, tear] {
            assert!((rho(at + 1e-12) - rho(at - 1e-12)).abs() < 1e-12);
            // The slope of the loss, 2 r dr/de, is the same on either side.
            let loss_slope = |e: f64| {
                let (r, dr) = capped(e, 1.0, wide, tear);
                2.0 * r * dr
            };
            let (below, above) = (loss_slope(at - 1e-9), loss_slope(at + 1e-9));
            assert!(
                (below - above).abs() < 1e-6 * below.abs(),
                "at {at}: {below} {above}"
            );
        }
        // A `tear` under `wide` is taken as `wide`: no jump, no root of a negative number.
        for e in [0.011, 0.02, 0.5] {
            assert_eq!(capped(e, 1.0, wide, 0.002), capped(e, 1.0, wide, wide));
            assert!(capped(e, 1.0, wide, 0.002).0.is_finite());
        }
        assert_eq!(rho(0.008), 0.008 * 0.008);
        // With Huber's loss alone two gaps of 20 mm excess cost less than one of 40 mm: the
        // misfit spreads; past `tear` one tear of 40 mm costs less than two gaps of 20: the
        // misfit gathers.
        let huber = |e: f64| capped(e, 1.0, wide, f64::INFINITY).0.powi(2);
        assert!(2.0 * huber(0.02) < huber(0.04));
        assert!(rho(0.04) < 2.0 * rho(0.02));
        // A slope past `tear` still pulls the tear's tiles together, weaker the wider.
        assert!(capped(0.05, 1.0, wide, tear).1 > capped(0.2, 1.0, wide, tear).1);
        assert!(capped(0.2, 1.0, wide, tear).1 > 0.0);
    }

    #[test]
    fn gradient_matches_finite_differences() {
        let (sizes, found, frames, surface) = setup();
        let bands: Vec<Option<BondBand>> = found
            .iter()
            .map(|c| {
                (c.sides[0].is_long()).then_some(BondBand {
                    nominal: 0.2,
                    tolerance: 0.1,
                })
            })
            .collect();
        let anchors: Vec<Frame> = frames
            .iter()
            .map(|f| Frame {
                origin: f.origin + Vector3::new(0.1, -0.05, 0.0),
                ..*f
            })
            .collect();
        // Every joint capped, then every other one closed (kept quadratic however wide).
        let every_other: Vec<bool> = (0..found.len()).map(|c| c % 2 == 0).collect();
        let mut values = Vec::new();
        for closing in [&[][..], &every_other[..]] {
            let problem = Problem {
                sizes: &sizes,
                contacts: &found,
                bands: &bands,
                anchors: &anchors,
                joint: 0.1,
                weights: Weights {
                    overlap_slope: 4.0,
                    narrow_slope: 2.0,
                    bond: 1.0,
                    anchor: 0.1,
                    edge: 4.0,
                    // Small enough that some of the jittered joints lie beyond them.
                    wide: 0.02,
                    tear: 0.03,
                },
                beyond_start: &[],
                surface: &surface,
                closing,
            };
            let beyond = vec![Vector3::zeros(); frames.len()];
            let eq = problem.normal_equations(&frames, &beyond);
            values.push(eq.value);
            let h = 1e-7;
            for t in 0..frames.len() {
                for k in 0..3 {
                    let mut step = Vector3::zeros();
                    step[k] = h;
                    let mut plus = frames.clone();
                    plus[t] = problem.moved(&frames[t], &step).0;
                    let mut minus = frames.clone();
                    minus[t] = problem.moved(&frames[t], &(-step)).0;
                    let numeric = (problem.value(&plus, &beyond) - problem.value(&minus, &beyond))
                        / (4.0 * h);
                    assert!(
                        (numeric - eq.g[t][k]).abs() < 1e-5 * (1.0 + numeric.abs()),
                        "tile {t} axis {k}: {numeric} vs {}",
                        eq.g[t][k]
                    );
                }
            }
        }
        // Joints wider than `wide` cost more closed than capped.
        assert!(values[1] > values[0], "{values:?}");
    }
}
