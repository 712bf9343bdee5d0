//! The part of the surface the caller left out of the pattern: the excluded quads (openings,
//! areas laid by hand). The fit's tears are not filled there ([`super::tears`]) and the
//! report's coverage does not count it as uncovered (`report::coverage`): before, an
//! opening excluded with `--exclude` was filled with pieces by the tear fill (34 of them in a
//! 61-face opening) or, without the fit, read as a coverage of 0.900 with a warning that
//! blamed units and remeshing. The fit and the cut to the boundary take the surface with an
//! opening there ([`ExcludedArea::opened`]): before, the fit slid the tiles around a 1 m
//! opening into it, covering half of it, and nothing said so.

use nalgebra::Point3;

use crate::geom::SurfaceIndex;
use crate::mesh::PolyMesh;

/// The excluded faces of a mesh (the quads, or the surface the caller excluded faces of), with
/// the closest-point index that tells whether a point of the surface lies over one of them.
pub struct ExcludedArea {
    index: SurfaceIndex,
    /// Per triangle of the index, its face.
    face_of: Vec<usize>,
    excluded: Vec<bool>,
}

impl ExcludedArea {
    /// The area of the faces `faces` of `mesh`; `None` when there are none.
    pub fn new(mesh: &PolyMesh, faces: &[usize]) -> Option<Self> {
        if faces.is_empty() {
            return None;
        }
        Some(Self {
            index: SurfaceIndex::from_polymesh(mesh),
            face_of: SurfaceIndex::polymesh_faces(mesh),
            excluded: mask(mesh.face_count(), faces),
        })
    }

    /// Whether the face closest to `q` is excluded.
    pub fn contains(&self, q: &Point3<f64>) -> bool {
        self.index
            .closest(&q.coords)
            .is_some_and(|on| self.excluded[self.face_of[on.triangle]])
    }

    /// `surface` with an opening where the area lies: without the faces whose centroid is
    /// over an excluded face (for the quads' area, the rule by which the quads took the
    /// surface's excluded faces, turned round), so that the fit keeps tiles out of it as out
    /// of any opening and the tiles are cut to its edge. `None` when no face lies there, or
    /// every face does.
    pub fn opened(&self, surface: &PolyMesh) -> Option<PolyMesh> {
        let over: Vec<bool> = (0..surface.face_count())
            .map(|f| self.contains(&surface.face_centroid(f)))
            .collect();
        without(surface, &over)
    }
}

/// Per face of a mesh of `count` faces, whether it is one of `faces` (indices beyond it are
/// ignored).
fn mask(count: usize, faces: &[usize]) -> Vec<bool> {
    let mut mask = vec![false; count];
    for &f in faces {
        if let Some(m) = mask.get_mut(f) {
            *m = true;
        }
    }
    mask
}

/// `surface` without the faces `left_out` (indices beyond it are ignored): an opening where
/// they lie. `None` when none of its faces is left out, or all are.
pub fn without_faces(surface: &PolyMesh, left_out: &[usize]) -> Option<PolyMesh> {
    without(surface, &mask(surface.face_count(), left_out))
}

/// `surface` without the faces `out` marks ([`without_faces`]).
fn without(surface: &PolyMesh, out: &[bool]) -> Option<PolyMesh> {
    let faces: Vec<Vec<usize>> = surface
        .faces()
        .iter()
        .zip(out)
        .filter(|&(_, &o)| !o)
        .map(|(face, _)| face.clone())
        .collect();
    if faces.len() == surface.face_count() {
        return None;
    }
    // A subset of a valid mesh's faces is valid (empty aside).
    PolyMesh::new(surface.positions().to_vec(), faces).ok()
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

    #[test]
    fn a_surface_is_opened_where_it_lies_over_the_excluded_quads() {
        // Quads of a 4 x 4 grid, the middle one left out; the surface the same grid split
        // into triangles, twice as fine.
        let quads = generate::grid(4, 4);
        let middle = (0..quads.face_count())
            .find(|&f| {
                let c = quads.face_centroid(f);
                (c.x - 1.5).abs() < 0.1 && (c.y - 1.5).abs() < 0.1
            })
            .unwrap();
        let fine = generate::grid(8, 8);
        let half: Vec<_> = fine.positions().iter().map(|p| p * 0.5).collect();
        let surface =
            generate::triangulate_quads(&PolyMesh::new(half, fine.faces().to_vec()).unwrap());
        let area = ExcludedArea::new(&quads, &[middle]).unwrap();
        let opened = area.opened(&surface).expect("an opening");
        // The 2 x 2 fine cells over the middle quad, two triangles each, are gone; every
        // other face is kept as it was.
        assert_eq!(opened.face_count(), surface.face_count() - 8);
        for f in 0..opened.face_count() {
            let c = opened.face_centroid(f);
            assert!(
                !((1.0..2.0).contains(&c.x) && (1.0..2.0).contains(&c.y)),
                "{c:?}"
            );
        }
        assert_eq!(opened.positions(), surface.positions());
        // The quads opened by themselves lose the quad; nothing to open, or all: none.
        assert_eq!(
            area.opened(&quads).unwrap().face_count(),
            quads.face_count() - 1
        );
        assert!(without_faces(&quads, &[]).is_none());
        let all: Vec<usize> = (0..quads.face_count()).collect();
        assert!(without_faces(&quads, &all).is_none());
        assert_eq!(without_faces(&quads, &[0, 99]).unwrap().face_count(), 15);
    }
}
