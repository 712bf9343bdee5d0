//! Which quad vertices slide on the input boundary and which sit on input corners: what
//! every step that moves vertices onto the input (cleanup, fitting, shape-up) keeps.

use nalgebra::Vector3;

use super::quadmesh::edge_faces;
use super::surface::Locator;

/// Which quad vertices slide on the input boundary and which sit on input corners, with the
/// neighbourhoods smoothing and shape-up need.
#[derive(Debug, Clone)]
pub(crate) struct Anchors {
    /// Neighbours along edges.
    pub nbrs: Vec<Vec<usize>>,
    /// Neighbours along boundary edges (empty for interior vertices).
    pub bnbrs: Vec<Vec<usize>>,
    /// Vertices held on an input corner.
    pub pinned: Vec<bool>,
}

impl Anchors {
    /// Finds the boundary of `faces` and moves the nearest boundary vertex onto each input
    /// corner (within 0.75 t).
    pub fn new(pos: &mut [Vector3<f64>], faces: &[Vec<usize>], locator: &Locator, t: f64) -> Self {
        let n = pos.len();
        let map = edge_faces(faces);
        let mut nbrs: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut bnbrs: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (&(a, b), list) in &map {
            nbrs[a].push(b);
            nbrs[b].push(a);
            if list.len() == 1 {
                bnbrs[a].push(b);
                bnbrs[b].push(a);
            }
        }
        let mut pinned = vec![false; n];
        for c in locator.corners() {
            let best = (0..n)
                .filter(|&v| !bnbrs[v].is_empty() && !pinned[v])
                .map(|v| ((pos[v] - c).norm(), v))
                .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
            if let Some((d, v)) = best {
                if d < 0.75 * t {
                    pos[v] = *c;
                    pinned[v] = true;
                }
            }
        }
        Self {
            nbrs,
            bnbrs,
            pinned,
        }
    }

    /// Where vertex `v` wanting to be at `p` may go: the closest boundary point for boundary vertices, the closest surface point otherwise.
    pub fn project(&self, locator: &Locator, v: usize, p: &Vector3<f64>) -> Vector3<f64> {
        if self.bnbrs[v].is_empty() {
            locator.closest(p).0
        } else {
            locator
                .closest_boundary(p)
                .unwrap_or_else(|| locator.closest(p).0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::quadmesh::samples::{grid, lines};
    use crate::remesh::surface::samples::sheet;

    #[test]
    fn corners_pin_the_nearest_boundary_vertex_and_projection_keeps_the_boundary() {
        // A 2 x 2 input, and a grid of quads inset by 0.1 on it.
        let mut input = sheet(4, 0.5, (0..0, 0..0), |_, _| 0.0);
        input.set_boundary_scale(0.25);
        let locator = Locator::new(&input);
        let (mut pos, faces) = grid(&lines(0.1, 1.9, 4), &lines(0.1, 1.9, 4));
        let anchors = Anchors::new(&mut pos, &faces, &locator, 0.5);
        let corners = [0, 4, 20, 24];
        for v in 0..pos.len() {
            assert_eq!(anchors.pinned[v], corners.contains(&v));
            let (i, j) = (v % 5, v / 5);
            let on_rim = i == 0 || i == 4 || j == 0 || j == 4;
            assert_eq!(anchors.bnbrs[v].len(), if on_rim { 2 } else { 0 });
            let expected = if corners.contains(&v) {
                2
            } else if on_rim {
                3
            } else {
                4
            };
            assert_eq!(anchors.nbrs[v].len(), expected);
        }
        assert_eq!(
            pos[24],
            Vector3::new(2.0, 2.0, 0.0),
            "moved onto the input's corner"
        );
        // A rim vertex goes onto the input's edge, an inner one onto the surface.
        let p = Vector3::new(0.1, 0.9, 0.3);
        assert!((anchors.project(&locator, 10, &p) - Vector3::new(0.0, 0.9, 0.0)).norm() < 1e-12);
        assert!((anchors.project(&locator, 12, &p) - Vector3::new(0.1, 0.9, 0.0)).norm() < 1e-12);
    }
}
