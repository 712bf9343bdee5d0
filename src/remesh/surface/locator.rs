//! Closest points on the input surface and along its boundary loops, through bounding volume
//! hierarchies over its triangles and boundary edges.

use nalgebra::Vector3;

use super::Surface;
use crate::geom::{Bvh, closest, fan};
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
        let corners = (0..surface.len())
            .filter(|&v| surface.is_corner(v))
            .map(|v| surface.pos[v])
            .collect();
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
        Self {
            tri_bvh: Bvh::of_simplices(&pos, &tris),
            seg_bvh: Bvh::of_simplices(&pos, &segments),
            pos,
            tris,
            segments,
            corners,
            seg_place,
            loops,
        }
    }

    /// Boundary vertices where the boundary turns by more than 50 degrees.
    pub fn corners(&self) -> &[Vector3<f64>] {
        &self.corners
    }

    /// Indexes any polygon mesh (fan-triangulated), for metrics on foreign quad meshes.
    pub fn from_polymesh(mesh: &PolyMesh) -> Self {
        let surface = Surface::build(
            mesh.positions().iter().map(|p| p.coords).collect(),
            fan(mesh).map(|(_, triangle)| triangle).collect(),
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
        Some(BoundaryPoint {
            lp,
            arc: arc.min(self.loops[lp].1).max(0.0),
            point,
        })
    }

    /// Length of boundary loop `lp`.
    pub fn loop_length(&self, lp: usize) -> f64 {
        self.loops[lp].1
    }

    /// The point at arc length `arc` (taken modulo the length) along boundary loop `lp`.
    pub fn boundary_point(&self, lp: usize, arc: f64) -> Vector3<f64> {
        let (order, length) = &self.loops[lp];
        if order.is_empty() || *length <= 0.0 {
            return order
                .first()
                .map_or_else(Vector3::zeros, |&i| self.pos[self.segments[i][0]]);
        }
        let arc = arc.rem_euclid(*length);
        let k = order
            .partition_point(|&i| self.seg_place[i].1 <= arc)
            .max(1)
            - 1;
        let i = order[k];
        let [a, b] = self.segments[i];
        let l = (self.pos[b] - self.pos[a]).norm();
        if l <= 0.0 {
            return self.pos[a];
        }
        self.pos[a]
            + (self.pos[b] - self.pos[a]) * ((arc - self.seg_place[i].1) / l).clamp(0.0, 1.0)
    }

    /// The point of loop `lp` nearest to `p` among those between arc `from` and `from +
    /// span` (going forward, wrapping), as (offset from `from`, point).
    pub fn closest_on_arc(
        &self,
        lp: usize,
        from: f64,
        span: f64,
        p: &Vector3<f64>,
    ) -> (f64, Vector3<f64>) {
        let (order, length) = &self.loops[lp];
        let mut best = (f64::INFINITY, 0.0, self.boundary_point(lp, from));
        for &i in order {
            let [a, b] = self.segments[i];
            let l = (self.pos[b] - self.pos[a]).norm();
            let start = (self.seg_place[i].1 - from).rem_euclid(*length);
            // Parts of this segment inside the window, as offsets.
            let (lo, hi) = if start + l <= *length {
                (start, start + l)
            } else {
                (start - *length, start - *length + l)
            };
            let (lo, hi) = (lo.max(0.0), hi.min(span));
            if lo > hi {
                continue;
            }
            let (qa, qb) = (
                self.boundary_point(lp, from + lo),
                self.boundary_point(lp, from + hi),
            );
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

#[cfg(test)]
mod tests {
    use super::super::samples::{sheet, wavy};
    use super::*;
    use crate::geom::numbers;

    /// A curved sheet (2 x 2) with a hole, at its boundary scale, and its locator.
    fn holed() -> (Surface, Locator) {
        let mut surface = sheet(16, 0.125, (5..9, 6..11), wavy);
        surface.set_boundary_scale(0.1);
        let locator = Locator::new(&surface);
        (surface, locator)
    }

    /// Query points around the sheet: over and under it, inside the hole, beyond the rim.
    fn queries(seed: u64, count: usize) -> Vec<Vector3<f64>> {
        let mut rnd = numbers(seed);
        (0..count)
            .map(|_| Vector3::new(rnd() * 3.0 - 0.5, rnd() * 3.0 - 0.5, rnd() * 1.2 - 0.6))
            .collect()
    }

    #[test]
    fn closest_point_on_the_surface_is_the_scan_over_all_triangles() {
        let (surface, locator) = holed();
        for p in queries(11, 400) {
            // Brute force: the nearest of all triangles, ties to the lower triangle.
            let (d2, i, q) = surface
                .tris
                .iter()
                .enumerate()
                .map(|(i, &[a, b, c])| {
                    let q =
                        closest::on_triangle(&p, &surface.pos[a], &surface.pos[b], &surface.pos[c]);
                    ((q - p).norm_squared(), i, q)
                })
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
                .unwrap();
            let (found, normal) = locator.closest(&p);
            assert_eq!(found, q, "query {p:?}");
            assert!((locator.distance(&p) - d2.sqrt()).abs() < 1e-12);
            let [a, b, c] = surface.tris[i];
            let face = (surface.pos[b] - surface.pos[a])
                .cross(&(surface.pos[c] - surface.pos[a]))
                .normalize();
            assert!((normal - face).norm() < 1e-12 && normal.z > 0.0);
        }
    }

    #[test]
    fn closest_point_on_the_boundary_is_the_scan_over_all_boundary_edges() {
        let (surface, locator) = holed();
        let loops = surface.boundary_loops();
        let segments = surface.boundary_segments();
        for p in queries(12, 400) {
            let (_, i, q) = segments
                .iter()
                .enumerate()
                .map(|(i, &[a, b])| {
                    let q = closest::on_segment(&p, &surface.pos[a], &surface.pos[b]);
                    ((q - p).norm_squared(), i, q)
                })
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
                .unwrap();
            assert_eq!(locator.closest_boundary(&p), Some(q), "query {p:?}");
            // Its place along its loop names the same point.
            let at = locator.closest_boundary_at(&p).unwrap();
            let lp = loops
                .iter()
                .position(|lp| lp.vertices.contains(&segments[i][0]))
                .unwrap();
            assert_eq!((at.lp, at.point), (lp, q));
            assert!(at.arc >= 0.0 && at.arc <= locator.loop_length(lp));
            assert!((locator.boundary_point(lp, at.arc) - q).norm() < 1e-12);
            // The nearest point of a window of the whole loop is that point too.
            // (At the loop's first vertex the offset may read 0 or the loop's length.)
            let length = locator.loop_length(lp);
            let (offset, r) = locator.closest_on_arc(lp, 0.0, length, &p);
            let apart = (offset - at.arc).rem_euclid(length);
            assert!(
                ((r - p).norm() - (q - p).norm()).abs() < 1e-12 && apart.min(length - apart) < 1e-9
            );
        }
    }

    #[test]
    fn loops_lengths_and_points_along_them() {
        let (surface, locator) = holed();
        let loops = surface.boundary_loops();
        assert_eq!(loops.len(), 2);
        for (id, lp) in loops.iter().enumerate() {
            assert_eq!(locator.loop_length(id), lp.length);
            // Arc lengths land on the loop's vertices, and wrap around.
            for (&v, &arc) in lp.vertices.iter().zip(&lp.arcs) {
                assert!((locator.boundary_point(id, arc) - surface.pos[v]).norm() < 1e-12);
                assert!(
                    (locator.boundary_point(id, arc - lp.length) - surface.pos[v]).norm() < 1e-12
                );
            }
        }
        // The outline's four corners, the hole's four.
        assert_eq!(locator.corners().len(), 8);
        // A window of the loop that leaves out the nearest point yields the nearest within it.
        let start = surface.pos[loops[0].vertices[0]];
        let (offset, q) = locator.closest_on_arc(0, 0.5, 1.0, &start);
        assert!(offset.abs() < 1e-12 && (q - locator.boundary_point(0, 0.5)).norm() < 1e-12);
    }

    #[test]
    fn a_surface_without_boundary_or_triangles_answers_without_panicking() {
        // The closed surface of a tetrahedron has no boundary.
        let pos = vec![Vector3::zeros(), Vector3::x(), Vector3::y(), Vector3::z()];
        let tetrahedron =
            Surface::build(pos, vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]], None);
        let locator = Locator::new(&tetrahedron);
        assert!(locator.closest_boundary(&Vector3::repeat(2.0)).is_none());
        assert!(
            (locator.closest(&Vector3::repeat(2.0)).0 - Vector3::repeat(1.0 / 3.0)).norm() < 1e-12
        );
        let empty = Locator::new(&Surface::build(Vec::new(), Vec::new(), None));
        assert_eq!(empty.closest(&Vector3::x()), (Vector3::x(), Vector3::z()));
    }
}
