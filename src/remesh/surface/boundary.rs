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
            let mut lp = BoundaryLoop {
                vertices: Vec::new(),
                arcs: Vec::new(),
                length: 0.0,
            };
            let mut v = start;
            while !seen[v] {
                seen[v] = true;
                lp.vertices.push(v);
                lp.arcs.push(lp.length);
                let Some((_, next)) = self.boundary[v] else {
                    break;
                };
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
        (0..self.len())
            .filter_map(|v| self.boundary[v].map(|(_, next)| [v, next]))
            .collect()
    }

    /// Walks from boundary vertex `v` along its loop (forwards: faces on the left), calling
    /// `go_on(w, arc)` at every vertex `w` reached, `arc` the length walked; stops when it
    /// returns false, back at `v`, where the boundary ends, or after a lap. Returns the last
    /// vertex reached (`v` when none is).
    fn walk_boundary(
        &self,
        v: usize,
        forward: bool,
        mut go_on: impl FnMut(usize, f64) -> bool,
    ) -> usize {
        let mut w = v;
        let mut arc = 0.0;
        for _ in 0..self.len() {
            let Some((prev, next)) = self.boundary[w] else {
                break;
            };
            let u = if forward { next } else { prev };
            arc += (self.pos[u] - self.pos[w]).norm();
            w = u;
            if w == v || !go_on(w, arc) {
                break;
            }
        }
        w
    }

    /// Measures boundary directions and corners over arcs of length `h` (about half a quad):
    /// shell boundaries from subdivided or trimmed meshes zig-zag at the triangle scale, and
    /// quads should follow the boundary's course, not its teeth.
    pub fn set_boundary_scale(&mut self, h: f64) {
        let n = self.len();
        // The vertex an arc of length `h` away (or the last before the walk ends).
        let walk =
            |v: usize, forward: bool, h: f64| self.walk_boundary(v, forward, |_, arc| arc < h);
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
                let (back, fwd) = (
                    walk(v, false, CORNER_SCALE * h),
                    walk(v, true, CORNER_SCALE * h),
                );
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
                self.walk_boundary(v, forward, |w, arc| {
                    if arc > h {
                        return false;
                    }
                    if turn[w] > turn[v] || (turn[w] == turn[v] && w < v) {
                        best = false;
                    }
                    true
                });
            }
            corner[v] = best;
        }
        let mut narrow = if h > 0.0 {
            self.narrow_parts(h / CORNER_SCALE)
        } else {
            vec![false; n]
        };
        // An acute corner cannot be followed by quads on both sides: rows along both sides
        // would have to end in a point. The boundary near it is left free, so the rows of the
        // wider side run out across the tip instead.
        if h > 0.0 {
            let reach = ACUTE_REACH * h;
            for v in 0..n {
                if !(corner[v] && turn[v] > ACUTE_TURN.to_radians()) {
                    continue;
                }
                narrow[v] = true;
                for forward in [false, true] {
                    self.walk_boundary(v, forward, |w, arc| {
                        if arc > reach {
                            return false;
                        }
                        narrow[w] = true;
                        true
                    });
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
        let grid = HashGrid::of_points(
            r,
            segments
                .iter()
                .map(|s| [Point3::from(self.pos[s[0]]), Point3::from(self.pos[s[1]])]),
        );
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
        let seam = self.seam_vertices();
        for lp in self.boundary_loops() {
            let has_corner = lp.vertices.iter().any(|&v| self.is_corner(v));
            let align = match mode {
                BoundaryAlignment::Always => true,
                BoundaryAlignment::Never => false,
                BoundaryAlignment::Auto => has_corner,
            };
            for v in lp.vertices {
                aligned[v] = align && !self.narrow[v] && !seam[v];
            }
        }
        aligned
    }

    /// Boundary vertices on a boundary edge of another loop: where the sheets of a surface cut
    /// open along a crease meet (`mesh::crease`). The quads cross such a seam as the field of
    /// their own sheet leads them and are trimmed to it, as a mason cuts the tiles of a web
    /// to the groin, so the seam is never aligned to.
    pub fn seam_vertices(&self) -> Vec<bool> {
        let mut seam = vec![false; self.len()];
        let loops = self.boundary_loops();
        let segments = self.boundary_segments();
        if loops.len() < 2 {
            return seam;
        }
        let mut loop_of = vec![usize::MAX; self.len()];
        for (i, lp) in loops.iter().enumerate() {
            for &v in &lp.vertices {
                loop_of[v] = i;
            }
        }
        let ends = |[a, b]: [usize; 2]| [Point3::from(self.pos[a]), Point3::from(self.pos[b])];
        let mean = segments
            .iter()
            .map(|&[a, b]| (self.pos[b] - self.pos[a]).norm())
            .sum::<f64>()
            / segments.len() as f64;
        let grid = HashGrid::of_points(mean, segments.iter().map(|&s| ends(s)));
        let near = 1e-6 * mean;
        for (v, flag) in seam.iter_mut().enumerate() {
            if loop_of[v] == usize::MAX {
                continue;
            }
            *flag = grid
                .near(&Point3::from(self.pos[v]), near)
                .iter()
                .any(|&s| {
                    let [a, b] = segments[s];
                    loop_of[a] != loop_of[v]
                        && (closest::on_segment(&self.pos[v], &self.pos[a], &self.pos[b])
                            - self.pos[v])
                            .norm()
                            <= near
                });
        }
        seam
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

#[cfg(test)]
mod tests {
    use super::super::samples::sheet;
    use super::*;
    use crate::geom::polygon;

    /// Counter-clockwise area of a loop seen from above.
    fn area(s: &Surface, lp: &BoundaryLoop) -> f64 {
        polygon::signed_area(
            &lp.vertices
                .iter()
                .map(|&v| [s.pos[v].x, s.pos[v].y])
                .collect::<Vec<_>>(),
        )
    }

    #[test]
    fn a_sheet_with_a_hole_has_two_loops_of_the_right_lengths() {
        // 10 x 10 cells of 0.5, a hole of 4 x 2 cells: loops of 20 and 6 edges.
        let s = sheet(10, 0.5, (3..7, 4..6), |_, _| 0.0);
        let loops = s.boundary_loops();
        assert_eq!(loops.len(), 2);
        let (outer, hole) = (&loops[0], &loops[1]);
        assert_eq!((outer.vertices.len(), hole.vertices.len()), (40, 12));
        assert!((outer.length - 20.0).abs() < 1e-12 && (hole.length - 6.0).abs() < 1e-12);
        // Faces on the left: the outline runs counter-clockwise, the hole clockwise.
        assert!((area(&s, outer) - 25.0).abs() < 1e-12 && (area(&s, hole) + 2.0).abs() < 1e-12);
        for lp in &loops {
            assert_eq!(lp.arcs[0], 0.0);
            assert_eq!(
                lp.vertices[0],
                *lp.vertices.iter().min().unwrap(),
                "starts at its lowest vertex"
            );
            for k in 1..lp.vertices.len() {
                let step = (s.pos[lp.vertices[k]] - s.pos[lp.vertices[k - 1]]).norm();
                assert!(
                    (lp.arcs[k] - lp.arcs[k - 1] - step).abs() < 1e-12
                        && (step - 0.5).abs() < 1e-12
                );
                assert_eq!(s.boundary[lp.vertices[k - 1]].unwrap().1, lp.vertices[k]);
            }
        }
        // Every boundary vertex is on exactly one loop, and nothing else is.
        let mut on_loop: Vec<usize> = loops
            .iter()
            .flat_map(|lp| lp.vertices.iter().copied())
            .collect();
        on_loop.sort_unstable();
        let boundary: Vec<usize> = (0..s.len()).filter(|&v| s.boundary[v].is_some()).collect();
        assert_eq!(on_loop, boundary);
        assert_eq!(s.boundary_segments().len(), 52);
    }

    #[test]
    fn the_corners_of_an_outline_and_a_hole_are_found_and_nothing_else() {
        let mut s = sheet(12, 0.5, (4..8, 5..8), |_, _| 0.0);
        s.set_boundary_scale(0.25);
        let corners: Vec<[f64; 2]> = (0..s.len())
            .filter(|&v| s.is_corner(v))
            .map(|v| [s.pos[v].x, s.pos[v].y])
            .collect();
        let mut expected: Vec<[f64; 2]> = vec![
            [0.0, 0.0],
            [6.0, 0.0],
            [0.0, 6.0],
            [6.0, 6.0],
            [2.0, 2.5],
            [4.0, 2.5],
            [2.0, 4.0],
            [4.0, 4.0],
        ];
        expected.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
        let mut found = corners.clone();
        found.sort_by(|a, b| a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0])));
        assert_eq!(found, expected);
        assert!(
            !s.narrow.iter().any(|&n| n),
            "no part is narrower than the scale"
        );
        // Boundary directions follow the outline: along +x on the bottom edge.
        let v = (0..s.len())
            .find(|&v| s.pos[v].x == 3.0 && s.pos[v].y == 0.0)
            .unwrap();
        let (din, dout) = s.bdirs[v].unwrap();
        assert!(din.normalize().x > 0.999 && dout.normalize().x > 0.999);
        // Both loops have corners, so Auto aligns both; Never aligns none.
        let boundary: Vec<bool> = s.boundary.iter().map(Option::is_some).collect();
        assert_eq!(s.aligned_boundary(BoundaryAlignment::Auto), boundary);
        assert_eq!(s.aligned_boundary(BoundaryAlignment::Always), boundary);
        assert!(
            !s.aligned_boundary(BoundaryAlignment::Never)
                .iter()
                .any(|&a| a)
        );
    }

    #[test]
    fn a_slot_narrower_than_the_scale_is_narrow_and_left_unaligned() {
        // A slot one cell wide cut from the top edge down to half the sheet's height.
        let cell = 0.25;
        let mut s = sheet(12, cell, (6..7, 6..12), |_, _| 0.0);
        s.set_boundary_scale(1.5 * cell);
        let aligned = s.aligned_boundary(BoundaryAlignment::Always);
        for v in (0..s.len()).filter(|&v| s.boundary[v].is_some()) {
            let (x, y) = (s.pos[v].x, s.pos[v].y);
            let slot_side = (x == 1.5 || x == 1.75) && y >= 2.0;
            let far = y == 0.0 || x == 0.0 || x == 3.0;
            if slot_side {
                assert!(s.narrow[v], "slot side at ({x}, {y}) is narrow");
                assert!(!s.corner[v] && !aligned[v]);
            }
            if far {
                assert!(!s.narrow[v], "outline at ({x}, {y}) is not narrow");
                assert!(aligned[v]);
            }
        }
    }
}
