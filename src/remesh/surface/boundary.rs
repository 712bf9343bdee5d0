//! The boundary of the working surface: its loops, the directions and corners of the
//! boundary seen at the scale of the quads (shell boundaries from subdivided or trimmed meshes
//! zig-zag at the triangle scale), the narrow parts quads cannot follow, and which loops the
//! quads are aligned to.

use nalgebra::Point3;

use super::Surface;
use crate::geom::{HashGrid, closest};
use crate::remesh::BoundaryAlignment;

/// A boundary loop of a [`Surface`].
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BoundaryLoop {
    /// Its vertices in order, faces on the left.
    pub vertices: Vec<usize>,
    /// Per vertex: the arc length from the first vertex.
    pub arcs: Vec<f64>,
    /// The summed length of its edges, the closing one included.
    pub length: f64,
}

impl Surface {
    /// The boundary loops, each from its first vertex on (the lowest of the loop) along the
    /// boundary with the faces on its left, in order of their first vertex. On non-manifold
    /// input a walk that reaches a vertex with no boundary successor ends there.
    pub fn boundary_loops(&self) -> Vec<BoundaryLoop> {
        let mut seen = vec![false; self.len()];
        let mut loops = Vec::new();
        for start in 0..self.len() {
            if seen[start] || self.boundary[start].is_none() {
                continue;
            }
            let mut lp = BoundaryLoop { vertices: Vec::new(), arcs: Vec::new(), length: 0.0 };
            let mut v = start;
            while !seen[v] {
                seen[v] = true;
                lp.vertices.push(v);
                lp.arcs.push(lp.length);
                let Some((_, next)) = self.boundary[v] else { break };
                lp.length += (self.pos[next] - self.pos[v]).norm();
                v = next;
            }
            loops.push(lp);
        }
        loops
    }

    /// The boundary edges, each as (vertex, its successor along the boundary), in order of
    /// the vertex.
    pub fn boundary_segments(&self) -> Vec<[usize; 2]> {
        (0..self.len()).filter_map(|v| self.boundary[v].map(|(_, next)| [v, next])).collect()
    }

    /// Measures boundary directions and corners over arcs of length `h` (about half a quad):
    /// shell boundaries from subdivided or trimmed meshes zig-zag at the triangle scale, and
    /// quads should follow the boundary's course, not its teeth.
    pub fn set_boundary_scale(&mut self, h: f64) {
        let n = self.len();
        let walk = |v: usize, forward: bool, h: f64| -> usize {
            let mut w = v;
            let mut acc = 0.0;
            for _ in 0..n {
                let Some((prev, next)) = self.boundary[w] else { break };
                let u = if forward { next } else { prev };
                acc += (self.pos[u] - self.pos[w]).norm();
                w = u;
                if acc >= h || w == v {
                    break;
                }
            }
            w
        };
        let mut bdirs = vec![None; n];
        let mut turn = vec![0.0; n];
        for v in 0..n {
            if self.boundary[v].is_some() {
                let (back, fwd) = (walk(v, false, h), walk(v, true, h));
                let din = self.pos[v] - self.pos[back];
                let dout = self.pos[fwd] - self.pos[v];
                bdirs[v] = Some((din, dout));
                // Corners are read at the scale of a whole quad: a boundary rounded with a
                // radius of about one quad is a corner for the quads.
                let (back, fwd) = (walk(v, false, CORNER_SCALE * h), walk(v, true, CORNER_SCALE * h));
                turn[v] = (self.pos[v] - self.pos[back]).angle(&(self.pos[fwd] - self.pos[v]));
                if turn[v].is_nan() {
                    turn[v] = 0.0;
                }
            }
        }
        let h = CORNER_SCALE * h;
        let threshold = CORNER_COS.acos();
        let mut corner = vec![false; n];
        for v in 0..n {
            if self.boundary[v].is_none() || turn[v] <= threshold {
                continue;
            }
            // Non-maximum suppression along the arc of length h on both sides.
            let mut best = true;
            for forward in [false, true] {
                let mut w = v;
                let mut acc = 0.0;
                for _ in 0..n {
                    let Some((prev, next)) = self.boundary[w] else { break };
                    let u = if forward { next } else { prev };
                    acc += (self.pos[u] - self.pos[w]).norm();
                    w = u;
                    if w == v || acc > h {
                        break;
                    }
                    if turn[w] > turn[v] || (turn[w] == turn[v] && w < v) {
                        best = false;
                    }
                }
            }
            corner[v] = best;
        }
        let mut narrow = if h > 0.0 { self.narrow_parts(h / CORNER_SCALE) } else { vec![false; n] };
        // An acute corner cannot be followed by quads on both sides: rows along both sides
        // would have to end in a point. The boundary near it is left free, so the rows of the
        // wider side run out across the tip instead.
        if h > 0.0 {
            let reach = ACUTE_REACH * h;
            for v in 0..n {
                if !(corner[v] && turn[v] > ACUTE_TURN.to_radians()) {
                    continue;
                }
                for forward in [false, true] {
                    let mut w = v;
                    let mut acc = 0.0;
                    narrow[v] = true;
                    for _ in 0..n {
                        let Some((prev, next)) = self.boundary[w] else { break };
                        let u = if forward { next } else { prev };
                        acc += (self.pos[u] - self.pos[w]).norm();
                        w = u;
                        if w == v || acc > reach {
                            break;
                        }
                        narrow[w] = true;
                    }
                }
            }
        }
        for v in 0..n {
            if narrow[v] {
                corner[v] = false;
            }
        }
        self.bdirs = bdirs;
        self.corner = corner;
        self.narrow = narrow;
    }

    /// Boundary vertices with another boundary stretch within `r` that is much farther away
    /// along the loop than in space (see [`Surface::narrow`]).
    fn narrow_parts(&self, r: f64) -> Vec<bool> {
        let n = self.len();
        // Arc length position and loop of every boundary vertex.
        let loops = self.boundary_loops();
        let mut arc = vec![0.0; n];
        let mut loop_of = vec![usize::MAX; n];
        for (id, lp) in loops.iter().enumerate() {
            for (&v, &s) in lp.vertices.iter().zip(&lp.arcs) {
                loop_of[v] = id;
                arc[v] = s;
            }
        }
        let segments = self.boundary_segments();
        if segments.is_empty() {
            return vec![false; n];
        }
        let grid = HashGrid::of_points(r, segments.iter().map(|s| [Point3::from(self.pos[s[0]]), Point3::from(self.pos[s[1]])]));
        let mut narrow = vec![false; n];
        for v in (0..n).filter(|&v| self.boundary[v].is_some()) {
            let p = self.pos[v];
            let id = loop_of[v];
            let length = loops[id].length;
            narrow[v] = grid.near(&Point3::from(p), r).into_iter().any(|i| {
                let [a, b] = segments[i];
                if loop_of[a] != id {
                    return false;
                }
                let q = closest::on_segment(&p, &self.pos[a], &self.pos[b]);
                let d = (q - p).norm();
                if d >= r {
                    return false;
                }
                let s = arc[a] + (q - self.pos[a]).norm();
                let along = (s - arc[v]).abs();
                let along = along.min(length - along);
                along > NARROW_RATIO * d.max(0.25 * r) + 1e-12
            });
        }
        narrow
    }

    /// Per vertex: true on boundary loops the quads should follow under `mode` (see
    /// [`BoundaryAlignment`]).
    pub fn aligned_boundary(&self, mode: BoundaryAlignment) -> Vec<bool> {
        let mut aligned = vec![false; self.len()];
        for lp in self.boundary_loops() {
            let has_corner = lp.vertices.iter().any(|&v| self.is_corner(v));
            let align = match mode {
                BoundaryAlignment::Always => true,
                BoundaryAlignment::Never => false,
                BoundaryAlignment::Auto => has_corner,
            };
            for v in lp.vertices {
                aligned[v] = align && !self.narrow[v];
            }
        }
        aligned
    }

    /// True at boundary corners (see [`Surface::set_boundary_scale`]).
    pub fn is_corner(&self, v: usize) -> bool {
        self.corner[v]
    }
}

/// Corners are measured over this multiple of the boundary scale.
const CORNER_SCALE: f64 = 2.0;

/// Boundary turning (degrees) above which a corner is acute (interior angle below 60).
const ACUTE_TURN: f64 = 120.0;

/// Arc length, in multiples of the corner scale, left free on each side of an acute corner.
const ACUTE_REACH: f64 = 3.0;

/// Arc-to-chord ratio above which two boundary points face each other across a narrow part.
const NARROW_RATIO: f64 = 2.5;

/// Cosine of the turning angle (50 degrees) above which a boundary vertex is a corner.
const CORNER_COS: f64 = 0.642_787_609_686_539_3;
