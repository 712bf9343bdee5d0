//! The designer's own direction field: one vector per input vertex or per input face (for
//! example principal stress or thrust directions from a structural analysis), the answer to
//! the paper's section 4.4, "aligning the orientation field with the direction of force flow
//! within the structure".
//!
//! This file only checks the vectors and carries them onto the remesher's working surface as
//! weighted samples per vertex; the 4-RoSy encoding, the blend with the curvature field and
//! the smoothing are the field solve's ([`super::field`]), written once for every source.

use nalgebra::Vector3;

use super::RemeshError;
use crate::mesh::PolyMesh;

/// Weighted unit vectors per vertex of the working surface.
pub(crate) type Samples = Vec<Vec<(Vector3<f64>, f64)>>;

/// Where the vectors of a [`UserField`] sit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldSite {
    /// One vector per input vertex, in vertex order.
    Vertices,
    /// One vector per input face, in face order (each face's vector counts at its corners
    /// with the face's area).
    Faces,
}

/// A direction field given by the designer. The vectors need not be unit, tangent or
/// consistently signed: each is projected into the tangent plane and only its direction
/// modulo 90 degrees counts (a cross follows the vector or its perpendicular). Where the
/// vectors are nearly normal to the surface, or neighbouring face vectors disagree, they pull
/// less and the field is interpolated from around them.
#[derive(Debug, Clone, PartialEq)]
pub struct UserField {
    /// The vectors, one per vertex or per face of the input mesh (see `site`).
    pub vectors: Vec<[f64; 3]>,
    /// Whether `vectors` are per vertex or per face.
    pub site: FieldSite,
    /// Share of the user field against the curvature field (or whatever
    /// [`super::FieldDirection`] gives), in `[0, 1]`: 1 follows the user vectors alone, 0
    /// the curvature alone (held just as firmly); in between both pull in proportion.
    pub weight: f64,
}

impl std::fmt::Display for FieldSite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FieldSite::Vertices => "vertex",
            FieldSite::Faces => "face",
        })
    }
}

impl UserField {
    /// A field with `vectors` per vertex or per face of `mesh`, decided by their count (per
    /// vertex when the mesh has as many vertices as faces).
    ///
    /// # Errors
    /// [`RemeshError::FieldCount`] when the count matches neither.
    pub fn for_mesh(
        mesh: &PolyMesh,
        vectors: Vec<[f64; 3]>,
        weight: f64,
    ) -> Result<Self, RemeshError> {
        let site = if vectors.len() == mesh.positions().len() {
            FieldSite::Vertices
        } else if vectors.len() == mesh.face_count() {
            FieldSite::Faces
        } else {
            return Err(RemeshError::FieldCount {
                given: vectors.len(),
                vertices: mesh.positions().len(),
                faces: mesh.face_count(),
            });
        };
        Ok(Self {
            vectors,
            site,
            weight,
        })
    }

    /// Checks the field against `mesh`: the count for its site, every vector finite and
    /// non-zero, the weight in `[0, 1]`.
    ///
    /// # Errors
    /// [`RemeshError::FieldCount`], [`RemeshError::BadFieldVector`] (the first bad index) or
    /// [`RemeshError::BadFieldWeight`].
    pub fn check(&self, mesh: &PolyMesh) -> Result<(), RemeshError> {
        let expected = match self.site {
            FieldSite::Vertices => mesh.positions().len(),
            FieldSite::Faces => mesh.face_count(),
        };
        if self.vectors.len() != expected {
            return Err(RemeshError::FieldCount {
                given: self.vectors.len(),
                vertices: mesh.positions().len(),
                faces: mesh.face_count(),
            });
        }
        if let Some((index, &vector)) = self.vectors.iter().enumerate().find(|(_, v)| {
            !v.iter().all(|c| c.is_finite())
                || v.iter().all(|&c| c == 0.0)
                || !Vector3::from(**v).norm().is_finite()
        }) {
            return Err(RemeshError::BadFieldVector {
                index,
                site: self.site,
                vector,
            });
        }
        if !(self.weight.is_finite() && (0.0..=1.0).contains(&self.weight)) {
            return Err(RemeshError::BadFieldWeight(self.weight));
        }
        Ok(())
    }

    /// The field on a mesh whose vertex `k` stands for vertex `source[k]` of the mesh this
    /// field was given for (a surface cut open along its creases): vectors per vertex are
    /// repeated on the copies, vectors per face kept.
    pub(crate) fn on_copies(&self, source: &[usize]) -> Self {
        let vectors = match self.site {
            FieldSite::Vertices => source.iter().map(|&v| self.vectors[v]).collect(),
            FieldSite::Faces => self.vectors.clone(),
        };
        Self {
            vectors,
            ..self.clone()
        }
    }

    /// The vectors as weighted samples on the working surface: per surface vertex, unit
    /// vectors with their weights. `surface_of[v]` is the surface vertex of input vertex `v`
    /// (`usize::MAX` when no face uses it), `count` the number of surface vertices.
    pub(crate) fn samples(&self, mesh: &PolyMesh, surface_of: &[usize], count: usize) -> Samples {
        let mut out = vec![Vec::new(); count];
        let unit = |v: &[f64; 3]| {
            let v = Vector3::from(*v);
            v / v.norm()
        };
        match self.site {
            FieldSite::Vertices => {
                for (v, vector) in self.vectors.iter().enumerate() {
                    if let Some(s) = surface_of.get(v).filter(|&&s| s != usize::MAX) {
                        out[*s].push((unit(vector), 1.0));
                    }
                }
            }
            FieldSite::Faces => {
                for (f, vector) in self.vectors.iter().enumerate() {
                    let area = mesh.face_area_vector(f).norm();
                    if !(area.is_finite() && area > 0.0) {
                        continue;
                    }
                    let d = unit(vector);
                    for &v in &mesh.faces()[f] {
                        out[surface_of[v]].push((d, area));
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    fn square() -> PolyMesh {
        // 3 x 2 vertices, 2 quads: 6 vertices, 2 faces.
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        PolyMesh::new(
            vec![
                p(0.0, 0.0),
                p(1.0, 0.0),
                p(2.0, 0.0),
                p(0.0, 1.0),
                p(1.0, 1.0),
                p(2.0, 1.0),
            ],
            vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4]],
        )
        .unwrap()
    }

    #[test]
    fn the_count_decides_the_site_and_a_wrong_count_names_both() {
        let m = square();
        let per_vertex = UserField::for_mesh(&m, vec![[1.0, 0.0, 0.0]; 6], 1.0).unwrap();
        assert_eq!(per_vertex.site, FieldSite::Vertices);
        let per_face = UserField::for_mesh(&m, vec![[1.0, 0.0, 0.0]; 2], 1.0).unwrap();
        assert_eq!(per_face.site, FieldSite::Faces);
        let err = UserField::for_mesh(&m, vec![[1.0, 0.0, 0.0]; 5], 1.0).unwrap_err();
        assert_eq!(
            err,
            RemeshError::FieldCount {
                given: 5,
                vertices: 6,
                faces: 2
            }
        );
        let text = err.to_string();
        assert!(
            text.contains("5 vectors") && text.contains("6 vertices"),
            "{text}"
        );
    }

    #[test]
    fn bad_vectors_and_weights_name_the_index() {
        let m = square();
        let mut vectors = vec![[0.0, 1.0, 0.0]; 6];
        vectors[4] = [0.0, 0.0, 0.0];
        let field = UserField::for_mesh(&m, vectors.clone(), 1.0).unwrap();
        let err = field.check(&m).unwrap_err();
        assert!(
            matches!(err, RemeshError::BadFieldVector { index: 4, .. }),
            "{err}"
        );
        assert!(err.to_string().contains("vertex 4"), "{err}");
        vectors[4] = [0.0, 1.0, 0.0];
        vectors[2] = [f64::NAN, 1.0, 0.0];
        let err = UserField::for_mesh(&m, vectors.clone(), 1.0)
            .unwrap()
            .check(&m)
            .unwrap_err();
        assert!(matches!(err, RemeshError::BadFieldVector { index: 2, .. }));
        // Finite components whose length overflows are refused too.
        let err = UserField::for_mesh(&m, vec![[1e308, 1e308, 0.0]; 2], 1.0)
            .unwrap()
            .check(&m)
            .unwrap_err();
        assert!(err.to_string().contains("face 0"), "{err}");
        vectors[2] = [0.0, 1.0, 0.0];
        for w in [-0.1, 1.5, f64::NAN] {
            let err = UserField::for_mesh(&m, vectors.clone(), w)
                .unwrap()
                .check(&m)
                .unwrap_err();
            assert!(matches!(err, RemeshError::BadFieldWeight(_)), "{err}");
        }
        // A field built for another mesh is caught by its count.
        let wrong = UserField {
            vectors: vec![[1.0, 0.0, 0.0]; 3],
            site: FieldSite::Faces,
            weight: 1.0,
        };
        assert!(matches!(
            wrong.check(&m),
            Err(RemeshError::FieldCount { given: 3, .. })
        ));
    }

    #[test]
    fn face_vectors_reach_every_corner_with_the_face_area() {
        let m = square();
        let field = UserField::for_mesh(&m, vec![[2.0, 0.0, 0.0], [0.0, 3.0, 0.0]], 1.0).unwrap();
        let identity: Vec<usize> = (0..6).collect();
        let samples = field.samples(&m, &identity, 6);
        // Vertices 1 and 4 are shared by both faces.
        assert_eq!(samples[0], vec![(Vector3::x(), 1.0)]);
        assert_eq!(samples[1], vec![(Vector3::x(), 1.0), (Vector3::y(), 1.0)]);
        assert_eq!(samples[5], vec![(Vector3::y(), 1.0)]);
    }
}
