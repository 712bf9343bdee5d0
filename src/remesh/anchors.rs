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
        Self { nbrs, bnbrs, pinned }
    }

    /// Where vertex `v` wanting to be at `p` may go: the closest boundary point for boundary vertices, the closest surface point otherwise.
    pub fn project(&self, locator: &Locator, v: usize, p: &Vector3<f64>) -> Vector3<f64> {
        if self.bnbrs[v].is_empty() {
            locator.closest(p).0
        } else {
            locator.closest_boundary(p).unwrap_or_else(|| locator.closest(p).0)
        }
    }
}
