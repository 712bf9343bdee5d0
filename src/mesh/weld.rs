//! Welding: joining vertices that lie (nearly) at the same place, as files without shared
//! vertices need (STL always, triangle soups exported as OBJ, PLY or OFF).

use std::collections::HashMap;

use foldhash::fast::FixedState;

use nalgebra::Point3;
use serde::Serialize;

use super::{Corners, FaceSet, FileNumbering};
use crate::geom::HashGrid;

/// Default weld tolerance as a fraction of the mesh's bounding-box diagonal: far below any
/// tile or face, far above the rounding of 32-bit floats (STL) and of six decimals (OBJ).
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-6;

/// What welding did.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct WeldSummary {
    /// Largest distance (model units) at which two vertices were joined; 0 joins only
    /// vertices with identical coordinates, and negative means welding was off.
    pub tolerance: f64,
    /// Vertices joined to an earlier one (the mesh has this many fewer).
    pub merged_vertices: usize,
    /// Faces removed because welding left them with fewer than three corners or made them
    /// repeat an earlier face (faces after the first removed one are renumbered).
    pub dropped_faces: usize,
    /// Vertices inserted into a boundary edge they lay on, closing a crack between patches
    /// meshed apart ([`super::zip`]).
    pub zipped_vertices: usize,
    /// Faces kept with fewer corners than the file gives them: two neighbouring corners at
    /// one place joined (a quad of QuadriFlow's with a collapsed edge becomes a triangle), or
    /// a corner given twice in a row (a triangle written as a quad `1 2 3 3`).
    pub shrunk_faces: usize,
}

impl WeldSummary {
    /// Nothing welded: welding was off.
    pub const OFF: Self = Self {
        tolerance: -1.0,
        merged_vertices: 0,
        dropped_faces: 0,
        zipped_vertices: 0,
        shrunk_faces: 0,
    };

    /// True when welding changed the mesh.
    pub fn changed(&self) -> bool {
        self.merged_vertices > 0 || self.dropped_faces > 0 || self.zipped_vertices > 0
    }
}

/// Joins every vertex to the first earlier vertex within `tolerance` (0: identical
/// coordinates only), then removes the faces this collapses and repeats, and those that
/// already were (fewer than three different corners, a face given twice, as STL and soup
/// exports carry): whether a face is dropped does not hang on whether some other vertex
/// was joined. Vertices keep their
/// order (joined ones are left out), faces theirs. Meshes welding cannot read (an index out
/// of range, a non-finite or too large coordinate) are returned as they are, for validation to name the
/// fault.
pub fn weld(
    positions: Vec<Point3<f64>>,
    faces: Vec<Vec<usize>>,
    tolerance: f64,
) -> (Vec<Point3<f64>>, Vec<Vec<usize>>, WeldSummary) {
    let (positions, faces, summary, _) = weld_traced(positions, faces, tolerance);
    (positions, faces, summary)
}

/// [`weld`], with where each face and vertex of the result comes from.
pub fn weld_traced(
    positions: Vec<Point3<f64>>,
    faces: Vec<Vec<usize>>,
    tolerance: f64,
) -> (
    Vec<Point3<f64>>,
    Vec<Vec<usize>>,
    WeldSummary,
    FileNumbering,
) {
    let tolerance = if tolerance.is_finite() {
        tolerance.max(0.0)
    } else {
        0.0
    };
    let untouched = WeldSummary {
        tolerance,
        merged_vertices: 0,
        dropped_faces: 0,
        zipped_vertices: 0,
        shrunk_faces: 0,
    };
    if !super::readable(&positions, &faces) {
        let same = FileNumbering::identity(faces.len(), positions.len());
        return (positions, faces, untouched, same);
    }
    let first = representatives(&positions, tolerance);
    let merged = first.iter().enumerate().filter(|&(i, &r)| i != r).count();
    // New numbers: the representatives in their order.
    let mut number = vec![usize::MAX; positions.len()];
    let mut kept = Vec::with_capacity(positions.len() - merged);
    for (i, &r) in first.iter().enumerate() {
        if i == r {
            number[i] = kept.len();
            kept.push(positions[i]);
        }
    }
    let mut seen = FaceSet::with_capacity(faces.len());
    let mut out = Vec::with_capacity(faces.len());
    let mut source = Vec::with_capacity(faces.len());
    let file_faces = faces.len();
    let mut dropped = 0;
    let mut shrunk = 0;
    for (i, face) in faces.into_iter().enumerate() {
        let given: Vec<usize> = face.iter().map(|&v| number[first[v]]).collect();
        let mut f = given.clone();
        // Corners joined along the face's edges collapse into one.
        f.dedup();
        while f.len() > 1 && f.first() == f.last() {
            f.pop();
        }
        let key = Corners::of(&f);
        if key.len() < 3 || seen.insert(key, out.len()).is_some() {
            dropped += 1;
            continue;
        }
        // A face the file gives with a corner twice in a row keeps its other corners: `1 2 3
        // 3` is how a triangle stored in a quad (Rhino's meshes: corner D = C) is written
        // out, and reads as the triangle. A corner repeated apart from itself (`1 2 1 3`)
        // leaves no polygon: the face is left as given, for validation to name.
        let pinched = {
            let mut own = f.clone();
            own.sort_unstable();
            own.dedup();
            own.len() < f.len()
        };
        if !pinched && f.len() < given.len() {
            shrunk += 1;
        }
        out.push(if pinched { given } else { f });
        source.push(i);
    }
    let vertex_of_file = first.iter().map(|&r| number[r]).collect();
    (
        kept,
        out,
        WeldSummary {
            tolerance,
            merged_vertices: merged,
            dropped_faces: dropped,
            zipped_vertices: 0,
            shrunk_faces: shrunk,
        },
        FileNumbering::new(file_faces, source, vertex_of_file),
    )
}

/// For each vertex, the first vertex (itself included) within `tolerance` of it among those
/// that are their own representative.
fn representatives(positions: &[Point3<f64>], tolerance: f64) -> Vec<usize> {
    if tolerance == 0.0 {
        // A fixed-seed hasher: only lookups shape the result.
        let mut index: HashMap<[u64; 3], usize, FixedState> =
            HashMap::with_capacity_and_hasher(positions.len(), FixedState::default());
        return positions
            .iter()
            .enumerate()
            // -0.0 and 0.0 are the same place.
            .map(|(i, p)| {
                *index
                    .entry([p.x, p.y, p.z].map(|c| (c + 0.0).to_bits()))
                    .or_insert(i)
            })
            .collect();
    }
    let mut grid = HashGrid::new(tolerance);
    let mut first = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        let near = grid
            .near(p, tolerance)
            .into_iter()
            .find(|&j| (positions[j] - p).norm() <= tolerance);
        match near {
            Some(j) => first.push(j),
            None => {
                grid.insert(i, p, p);
                first.push(i);
            }
        }
    }
    first
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point3<f64> {
        Point3::new(x, y, 0.0)
    }

    #[test]
    fn a_quad_with_a_collapsed_edge_is_a_triangle_counted_as_shrunk() {
        // A quad whose corners 2 and 3 lie at one place (QuadriFlow leaves such quads), a
        // second face removed as collapsed, and a plain quad after them.
        let positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(1.0, 1.0),
            p(2.0, 0.0),
            p(2.0, 1.0),
        ];
        let faces = vec![vec![0, 1, 2, 3], vec![2, 3, 1], vec![1, 4, 5, 2]];
        let (_, welded, summary, numbering) = weld_traced(positions, faces, 1e-9);
        assert_eq!(welded, vec![vec![0, 1, 2], vec![1, 3, 4, 2]]);
        assert_eq!((summary.shrunk_faces, summary.dropped_faces), (1, 1));
        assert_eq!(numbering.file_face(1), 2);
        assert_eq!(numbering.vertices_from_file(&[0, 1, 2, 3, 4, 5])[2], 2);
    }

    #[test]
    fn a_triangle_soup_becomes_a_mesh() {
        // Two triangles of a square, each with its own corners, one corner off by 1e-9.
        let positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(0.0, 0.0),
            p(1.0, 1.0 + 1e-9),
            p(0.0, 1.0),
        ];
        let faces = vec![vec![0, 1, 2], vec![3, 4, 5]];
        let (kept, welded, summary) = weld(positions.clone(), faces.clone(), 1e-6);
        assert_eq!(kept.len(), 4);
        assert_eq!(welded, vec![vec![0, 1, 2], vec![0, 2, 3]]);
        assert_eq!(summary.merged_vertices, 2);
        // Exact welding leaves the corner that is off apart.
        let (kept, _, summary) = weld(positions, faces, 0.0);
        assert_eq!(kept.len(), 5);
        assert_eq!(summary.merged_vertices, 1);
    }

    #[test]
    fn collapsed_and_repeated_faces_are_dropped() {
        let positions = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1e-9), p(0.0, 1.0)];
        let faces = vec![vec![0, 1, 3], vec![0, 2, 1], vec![3, 2, 0]];
        let (kept, faces, summary) = weld(positions, faces, 1e-6);
        assert_eq!(kept.len(), 3);
        // The sliver collapses; the last face repeats the first once 2 is 1.
        assert_eq!(faces, vec![vec![0, 1, 2]]);
        assert_eq!(summary.dropped_faces, 2);
    }

    #[test]
    fn faces_collapsed_or_repeated_in_the_file_are_dropped_with_nothing_to_join() {
        // No two vertices within the tolerance, but a face with a repeated corner and a face
        // given twice (in the other turn), as exports carry them.
        let positions = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        let faces = vec![vec![0, 1, 2], vec![0, 2, 2], vec![0, 2, 3], vec![2, 0, 1]];
        let (kept, faces, summary) = weld(positions, faces, 1e-6);
        assert_eq!(kept.len(), 4);
        assert_eq!(faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
        assert_eq!((summary.merged_vertices, summary.dropped_faces), (0, 2));
        assert!(summary.changed());
    }

    #[test]
    fn a_triangle_written_as_a_quad_reads_as_the_triangle_and_a_pinched_face_is_left() {
        // `1 2 3 3`, as a quad face of Rhino's holding a triangle is written out; `1 2 1 3`
        // comes back as given, for validation to refuse.
        let positions = vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)];
        let faces = vec![vec![0, 1, 2, 2], vec![0, 2, 3, 3]];
        let (kept, faces, summary) = weld(positions.clone(), faces, 1e-6);
        assert_eq!(kept.len(), 4);
        assert_eq!(faces, vec![vec![0, 1, 2], vec![0, 2, 3]]);
        assert_eq!((summary.shrunk_faces, summary.dropped_faces), (2, 0));
        let (_, faces, _) = weld(positions, vec![vec![0, 1, 0, 2]], 1e-6);
        assert_eq!(faces, vec![vec![0, 1, 0, 2]]);
    }

    #[test]
    fn unreadable_meshes_are_left_for_validation() {
        let positions = vec![p(0.0, 0.0), p(0.0, 0.0), p(1.0, 0.0)];
        let faces = vec![vec![0, 1, 7]];
        let (kept, same, summary) = weld(positions, faces.clone(), 1e-6);
        assert_eq!((kept.len(), same), (3, faces));
        assert!(!summary.changed());
    }
}
