//! Closest points on the input surface and along its boundary loops, through bounding volume
//! hierarchies over its triangles and boundary edges.

use nalgebra::Vector3;

use super::Surface;
use crate::geom::{Bvh, closest};
use crate::mesh::PolyMesh;

/// Closest points on the input surface and on its boundary curves.
#[derive(Debug, Clone)]
pub(crate) struct Locator {
    pos: Vec<Vector3<f64>>,
    tris: Vec<[usize; 3]>,
    segments: Vec<[usize; 2]>,
    corners: Vec<Vector3<f64>>,
    tri_bvh: Bvh,
    seg_bvh: Bvh,
    /// Per segment: its boundary loop and the arc length of its start along that loop.
    seg_place: Vec<(usize, f64)>,
    /// Per boundary loop: its segments in order and its length.
    loops: Vec<(Vec<usize>, f64)>,
}

/// A point on the input boundary: which loop, how far along it, where.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BoundaryPoint {
    /// The boundary loop.
    pub lp: usize,
    /// Arc length from the loop's start, in `[0, length)`.
    pub arc: f64,
    /// The point.
    pub point: Vector3<f64>,
}

impl Locator {
    /// Indexes the triangles and boundary edges of `surface` (whose corners are those of
    /// its boundary scale).
    pub fn new(surface: &Surface) -> Self {
        let pos = surface.pos.clone();
        let tris = surface.tris.clone();
        let segments = surface.boundary_segments();
        let corners = (0..surface.len()).filter(|&v| surface.is_corner(v)).map(|v| surface.pos[v]).collect();
        let tri_boxes: Vec<_> = tris
            .iter()
            .map(|t| {
                let (a, b, c) = (pos[t[0]], pos[t[1]], pos[t[2]]);
                (a.inf(&b).inf(&c), a.sup(&b).sup(&c))
            })
            .collect();
        let seg_boxes: Vec<_> = segments.iter().map(|s| (pos[s[0]].inf(&pos[s[1]]), pos[s[0]].sup(&pos[s[1]]))).collect();
        // Each boundary vertex starts at most one segment; a loop's segments are those that
        // start at its vertices.
        let mut starting = vec![usize::MAX; pos.len()];
        for (i, sg) in segments.iter().enumerate() {
            starting[sg[0]] = i;
        }
        let mut seg_place = vec![(usize::MAX, 0.0); segments.len()];
        let mut loops = Vec::new();
        for (id, lp) in surface.boundary_loops().into_iter().enumerate() {
            let mut order = Vec::with_capacity(lp.vertices.len());
            for (&v, &arc) in lp.vertices.iter().zip(&lp.arcs) {
                let i = starting[v];
                if i != usize::MAX {
                    seg_place[i] = (id, arc);
                    order.push(i);
                }
            }
            loops.push((order, lp.length));
        }
        Self { tri_bvh: Bvh::new(&tri_boxes), seg_bvh: Bvh::new(&seg_boxes), pos, tris, segments, corners, seg_place, loops }
    }

    /// Boundary vertices where the boundary turns by more than 50 degrees.
    pub fn corners(&self) -> &[Vector3<f64>] {
        &self.corners
    }

    /// Indexes any polygon mesh (fan-triangulated), for metrics on foreign quad meshes.
    pub fn from_polymesh(mesh: &PolyMesh) -> Self {
        let surface = Surface::build(
            mesh.positions().iter().map(|p| p.coords).collect(),
            mesh.faces().iter().flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]])).collect(),
            None,
        );
        Self::new(&surface)
    }

    /// Closest point on the boundary curves with its place along its loop.
    pub fn closest_boundary_at(&self, p: &Vector3<f64>) -> Option<BoundaryPoint> {
        let (i, _, point) = self.seg_bvh.nearest(p, |i| {
            let [a, b] = self.segments[i];
            let q = closest::on_segment(p, &self.pos[a], &self.pos[b]);
            ((q - p).norm_squared(), q)
        })?;
        let (lp, start) = self.seg_place[i];
        let arc = start + (point - self.pos[self.segments[i][0]]).norm();
        Some(BoundaryPoint { lp, arc: arc.min(self.loops[lp].1).max(0.0), point })
    }

    /// Length of boundary loop `lp`.
    pub fn loop_length(&self, lp: usize) -> f64 {
        self.loops[lp].1
    }

    /// The point at arc length `arc` (taken modulo the length) along boundary loop `lp`.
    pub fn boundary_point(&self, lp: usize, arc: f64) -> Vector3<f64> {
        let (order, length) = &self.loops[lp];
        if order.is_empty() || *length <= 0.0 {
            return order.first().map_or_else(Vector3::zeros, |&i| self.pos[self.segments[i][0]]);
        }
        let arc = arc.rem_euclid(*length);
        let k = order.partition_point(|&i| self.seg_place[i].1 <= arc).max(1) - 1;
        let i = order[k];
        let [a, b] = self.segments[i];
        let l = (self.pos[b] - self.pos[a]).norm();
        if l <= 0.0 {
            return self.pos[a];
        }
        self.pos[a] + (self.pos[b] - self.pos[a]) * ((arc - self.seg_place[i].1) / l).clamp(0.0, 1.0)
    }

    /// The point of loop `lp` nearest to `p` among those between arc `from` and `from +
    /// span` (going forward, wrapping), as (offset from `from`, point).
    pub fn closest_on_arc(&self, lp: usize, from: f64, span: f64, p: &Vector3<f64>) -> (f64, Vector3<f64>) {
        let (order, length) = &self.loops[lp];
        let mut best = (f64::INFINITY, 0.0, self.boundary_point(lp, from));
        for &i in order {
            let [a, b] = self.segments[i];
            let l = (self.pos[b] - self.pos[a]).norm();
            let start = (self.seg_place[i].1 - from).rem_euclid(*length);
            // Parts of this segment inside the window, as offsets.
            let (lo, hi) = if start + l <= *length { (start, start + l) } else { (start - *length, start - *length + l) };
            let (lo, hi) = (lo.max(0.0), hi.min(span));
            if lo > hi {
                continue;
            }
            let (qa, qb) = (self.boundary_point(lp, from + lo), self.boundary_point(lp, from + hi));
            let q = closest::on_segment(p, &qa, &qb);
            let d = (q - p).norm_squared();
            if d < best.0 {
                let along = if hi > lo { lo + (q - qa).norm() } else { lo };
                best = (d, along, q);
            }
        }
        (best.1, best.2)
    }

    /// Closest point on the surface, and its triangle's unit normal.
    pub fn closest(&self, p: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        match self.tri_bvh.nearest(p, |i| {
            let [a, b, c] = self.tris[i];
            let q = closest::on_triangle(p, &self.pos[a], &self.pos[b], &self.pos[c]);
            ((q - p).norm_squared(), q)
        }) {
            Some((i, _, q)) => {
                let [a, b, c] = self.tris[i];
                let n = (self.pos[b] - self.pos[a]).cross(&(self.pos[c] - self.pos[a]));
                (q, n.try_normalize(1e-300).unwrap_or_else(Vector3::z))
            }
            None => (*p, Vector3::z()),
        }
    }

    /// Distance to the surface.
    pub fn distance(&self, p: &Vector3<f64>) -> f64 {
        (self.closest(p).0 - p).norm()
    }

    /// Closest point on the boundary curves, if the surface has a boundary.
    pub fn closest_boundary(&self, p: &Vector3<f64>) -> Option<Vector3<f64>> {
        self.closest_boundary_at(p).map(|b| b.point)
    }
}
