//! The part of the surface the caller left out of the pattern: the excluded quads (openings,
//! areas laid by hand). The fit's tears are not filled there ([`super::tears`]) and the
//! report's coverage does not count it as uncovered (`report::coverage`): before, an
//! opening excluded with `--exclude` was filled with pieces by the tear fill (34 of them in a
//! 61-face opening) or, without the fit, read as a coverage of 0.900 with a warning that
//! blamed units and remeshing.

use nalgebra::Point3;

use crate::geom::SurfaceIndex;
use crate::mesh::PolyMesh;

/// The excluded quads of a quad mesh, with the closest-point index that tells whether a point
/// of the surface lies over one of them.
pub struct ExcludedArea {
    index: SurfaceIndex,
    /// Per triangle of the index, its quad.
    quad_of: Vec<usize>,
    excluded: Vec<bool>,
}

impl ExcludedArea {
    /// The area of the quads `faces` of `quads`; `None` when there are none.
    pub fn new(quads: &PolyMesh, faces: &[usize]) -> Option<Self> {
        if faces.is_empty() {
            return None;
        }
        let mut excluded = vec![false; quads.face_count()];
        for &f in faces {
            if let Some(e) = excluded.get_mut(f) {
                *e = true;
            }
        }
        Some(Self {
            index: SurfaceIndex::from_polymesh(quads),
            quad_of: SurfaceIndex::polymesh_faces(quads),
            excluded,
        })
    }

    /// Whether the quad closest to `q` is excluded.
    pub fn contains(&self, q: &Point3<f64>) -> bool {
        self.index
            .closest(&q.coords)
            .is_some_and(|on| self.excluded[self.quad_of[on.triangle]])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;

    #[test]
    fn a_point_over_an_excluded_quad_is_in_the_area_and_others_are_not() {
        let grid = generate::grid(4, 4);
        let middle = (0..grid.face_count())
            .find(|&f| {
                let c = grid.face_centroid(f);
                (c.x - 1.5).abs() < 0.1 && (c.y - 1.5).abs() < 0.1
            })
            .expect("a quad at (1.5, 1.5)");
        let area = ExcludedArea::new(&grid, &[middle]).unwrap();
        assert!(area.contains(&Point3::new(1.5, 1.5, 0.2)));
        assert!(!area.contains(&Point3::new(0.5, 0.5, 0.0)));
        assert!(ExcludedArea::new(&grid, &[]).is_none());
    }
}
