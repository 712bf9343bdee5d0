//! Polygon meshes: the data every stage reads.
//!
//! A [`PolyMesh`] keeps vertex positions and faces exactly in the order they were given, so
//! face indices in results (pairs, unpaired faces, tiles) refer to the caller's own numbering
//! (OBJ order for files). [`PolyMesh::new`] validates everything the later stages rely on and
//! names the offending face or vertex when it refuses a mesh.

pub mod crease;
mod error;
mod face_set;
pub mod generate;
pub mod io;
mod numbering;
pub mod obj;
pub mod orient;
pub mod simplify;
mod topology;
pub mod weld;
pub mod zip;

pub use error::MeshError;
pub(crate) use face_set::{Corners, FaceSet};
pub use numbering::{FileNumbering, NotInMesh};
pub use topology::{Edge, PieceAreas, Topology};

use nalgebra::{Point3, Vector3};

/// Most vertices one mesh may have: every stage together needs about a kilobyte per face at
/// its peak, so a mesh at the limits needs some 4 GB.
pub const MAX_VERTICES: usize = 4_000_000;
/// Most faces one mesh may have (see [`MAX_VERTICES`]).
pub const MAX_FACES: usize = 4_000_000;
/// Most face indices (the sum of the faces' sizes) one mesh may have.
pub const MAX_INDICES: usize = 16_000_000;
/// Largest coordinate magnitude a vertex may have. A kilometre in millimetres is 1e6; beyond
/// 1e12 products of coordinates (areas, normals, volumes of the later stages) would come
/// close to overflowing and a tile's grid cells would no longer fit an integer.
pub const MAX_COORDINATE: f64 = 1e12;

/// Whether `p` is a coordinate triple validation accepts: finite, no larger than
/// [`MAX_COORDINATE`].
pub(crate) fn usable_point(p: &Point3<f64>) -> bool {
    p.coords
        .iter()
        .all(|c| c.is_finite() && c.abs() <= MAX_COORDINATE)
}

/// Whether every position is [`usable_point`] and every face index names one: what the
/// repairs done while reading (welding, zipping) need before they touch a mesh, leaving
/// anything else for validation to name.
pub(crate) fn readable(positions: &[Point3<f64>], faces: &[Vec<usize>]) -> bool {
    positions.iter().all(usable_point) && faces.iter().flatten().all(|&v| v < positions.len())
}

/// Checks counts against [`MAX_VERTICES`], [`MAX_FACES`] and [`MAX_INDICES`] before anything
/// is allocated for them.
///
/// # Errors
/// [`MeshError::TooLarge`] naming the first count over its limit.
pub fn check_size(vertices: usize, faces: usize, indices: usize) -> Result<(), MeshError> {
    for (what, count, limit) in [
        ("vertices", vertices, MAX_VERTICES),
        ("faces", faces, MAX_FACES),
        ("face indices", indices, MAX_INDICES),
    ] {
        if count > limit {
            return Err(MeshError::TooLarge { what, count, limit });
        }
    }
    Ok(())
}

/// The first vertex of `face` (in face order) that appears again later in it. Linear time, so
/// that one huge face cannot stall validation.
fn first_repeated(face: &[usize]) -> Option<usize> {
    if face.len() <= 16 {
        return face
            .iter()
            .enumerate()
            .find(|&(k, v)| face[k + 1..].contains(v))
            .map(|(_, &v)| v);
    }
    let mut last = std::collections::HashMap::with_capacity(face.len());
    for (k, &v) in face.iter().enumerate() {
        last.insert(v, k);
    }
    face.iter()
        .enumerate()
        .find(|&(k, v)| last[v] > k)
        .map(|(_, &v)| v)
}

/// A validated polygon surface mesh: positions (f64) and faces as lists of vertex indices.
///
/// Invariants established by [`PolyMesh::new`]: at most [`MAX_VERTICES`] vertices,
/// [`MAX_FACES`] faces and [`MAX_INDICES`] face indices; at least one face; finite
/// coordinates no larger than [`MAX_COORDINATE`]; every face has at least three distinct,
/// in-range vertex indices; no two faces have the same vertices; no edge is shared by more
/// than two faces; faces sharing an edge run along it in opposite directions.
///
/// Accepted as they are: zero-area faces, vertices where pieces touch (non-manifold
/// vertices), disconnected pieces, vertices no face uses, any mix of triangles, quads and
/// n-gons.
#[derive(Debug, Clone, PartialEq)]
pub struct PolyMesh {
    positions: Vec<Point3<f64>>,
    faces: Vec<Vec<usize>>,
}

impl PolyMesh {
    /// Validates and builds a mesh.
    ///
    /// # Errors
    /// The first problem found, in this order: too large, empty mesh, non-finite coordinate,
    /// coordinate too large, face with fewer than three vertices, index out of range,
    /// repeated index in a face, duplicate face, non-manifold edge, inconsistent orientation.
    pub fn new(positions: Vec<Point3<f64>>, faces: Vec<Vec<usize>>) -> Result<Self, MeshError> {
        check_size(
            positions.len(),
            faces.len(),
            faces.iter().map(Vec::len).sum(),
        )?;
        if faces.is_empty() || positions.is_empty() {
            return Err(MeshError::Empty {
                vertices: positions.len(),
                faces: faces.len(),
            });
        }
        if let Some(vertex) = positions
            .iter()
            .position(|p| !p.coords.iter().all(|c| c.is_finite()))
        {
            return Err(MeshError::NonFiniteCoordinate { vertex });
        }
        if let Some(vertex) = positions
            .iter()
            .position(|p| p.coords.amax() > MAX_COORDINATE)
        {
            let value = positions[vertex].coords.amax();
            return Err(MeshError::CoordinateTooLarge {
                vertex,
                value,
                limit: MAX_COORDINATE,
            });
        }
        for (face, indices) in faces.iter().enumerate() {
            if indices.len() < 3 {
                return Err(MeshError::TooFewVertices {
                    face,
                    count: indices.len(),
                });
            }
            if let Some(&index) = indices.iter().find(|&&i| i >= positions.len()) {
                return Err(MeshError::IndexOutOfRange {
                    face,
                    index,
                    vertex_count: positions.len(),
                });
            }
            if let Some(vertex) = first_repeated(indices) {
                return Err(MeshError::RepeatedIndex { face, vertex });
            }
        }
        let mut seen = FaceSet::with_capacity(faces.len());
        for (face, indices) in faces.iter().enumerate() {
            if let Some(first) = seen.insert(Corners::of(indices), face) {
                return Err(MeshError::DuplicateFace { face, first });
            }
        }
        let mesh = Self { positions, faces };
        let topology = Topology::new(&mesh)?;
        if let Err(disagree) = topology.check_orientation(&mesh) {
            // Say so when no turning of faces can help.
            let mut faces = mesh.faces.clone();
            return Err(orient::orient(&mut faces).err().unwrap_or(disagree));
        }
        Ok(mesh)
    }

    /// Vertex positions in input order.
    pub fn positions(&self) -> &[Point3<f64>] {
        &self.positions
    }

    /// Faces in input order, each a list of vertex indices.
    pub fn faces(&self) -> &[Vec<usize>] {
        &self.faces
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// True when face `f` has four vertices; only quads can take part in a tile.
    pub fn is_quad(&self, f: usize) -> bool {
        self.faces[f].len() == 4
    }

    /// Positions of the corners of face `f`, in face order.
    pub fn face_points(&self, f: usize) -> impl Iterator<Item = Point3<f64>> + '_ {
        self.faces[f].iter().map(|&v| self.positions[v])
    }

    /// Vertex centroid of face `f` (the paper's face centroid, section 3.5).
    pub fn face_centroid(&self, f: usize) -> Point3<f64> {
        let sum = self
            .face_points(f)
            .fold(Vector3::zeros(), |acc, p| acc + p.coords);
        Point3::from(sum / self.faces[f].len() as f64)
    }

    /// Area-weighted normal of face `f` (Newell's method): its length is the area of a planar
    /// face, and its direction follows the face's vertex order.
    pub fn face_area_vector(&self, f: usize) -> Vector3<f64> {
        let points: Vec<_> = self.face_points(f).collect();
        let mut n = Vector3::zeros();
        for (i, p) in points.iter().enumerate() {
            let q = points[(i + 1) % points.len()];
            n += p.coords.cross(&q.coords);
        }
        n * 0.5
    }

    /// Axis-aligned bounding box `(min, max)`.
    pub fn bounding_box(&self) -> (Point3<f64>, Point3<f64>) {
        let mut min = self.positions[0];
        let mut max = self.positions[0];
        for p in &self.positions {
            min = min.inf(p);
            max = max.sup(p);
        }
        (min, max)
    }

    /// Total face area.
    pub fn area(&self) -> f64 {
        (0..self.faces.len())
            .map(|f| self.face_area_vector(f).norm())
            .sum()
    }
}
