//! The file's numbering of faces and vertices against the mesh read from it.
//!
//! Reading a file can remove faces (welding collapses them, or a face repeats another),
//! split triangles (zipping a crack, [`super::zip`]) and join vertices ([`super::weld`]).
//! Users count faces and vertices in the file, as every other tool shows them to them: a
//! zones file, a forced pair, a per-face field or the faces in `match`'s JSON are numbered
//! in the file, so the front ends translate through a [`FileNumbering`] in both directions.

/// A face number of the file that names no face of the mesh read from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NotInMesh {
    /// Beyond the file's last face.
    OutOfRange {
        /// The number given.
        face: usize,
        /// Faces in the file.
        file_faces: usize,
    },
    /// A face of the file that reading removed (collapsed by welding, or a repeat).
    Removed {
        /// The number given.
        face: usize,
    },
}

impl std::fmt::Display for NotInMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            NotInMesh::OutOfRange { face, file_faces } => write!(
                f,
                "face {face} does not exist (the file has {file_faces} faces, counted from 0: the last is {})",
                file_faces.saturating_sub(1)
            ),
            NotInMesh::Removed { face } => write!(
                f,
                "face {face} of the file was removed when it was read (welding collapsed it, or it repeats an earlier face); leave it out, or give --weld off to keep every face as the file has it"
            ),
        }
    }
}

impl std::error::Error for NotInMesh {}

/// Where each face and vertex of a mesh comes from in the file it was read from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileNumbering {
    /// Faces in the file.
    file_faces: usize,
    /// Per face of the mesh, the file's face it is (or is part of).
    face_source: Vec<usize>,
    /// Per face of the file, the mesh's face it is (the first of its parts), if any.
    face_of_file: Vec<Option<usize>>,
    /// Per vertex of the file, the mesh's vertex it became.
    vertex_of_file: Vec<usize>,
    /// Per vertex of the mesh, the first file vertex that became it (itself if none did).
    vertex_source: Vec<usize>,
}

impl FileNumbering {
    /// The numbering of a mesh read as the file has it: `faces` faces, `vertices` vertices.
    pub fn identity(faces: usize, vertices: usize) -> Self {
        Self::new(faces, (0..faces).collect(), (0..vertices).collect())
    }

    /// A numbering from the file face of each mesh face (each below `file_faces`) and the
    /// mesh vertex of each file vertex.
    pub(crate) fn new(
        file_faces: usize,
        face_source: Vec<usize>,
        vertex_of_file: Vec<usize>,
    ) -> Self {
        let mut face_of_file = vec![None; file_faces];
        for (face, &f) in face_source.iter().enumerate() {
            face_of_file[f].get_or_insert(face);
        }
        let vertices = vertex_of_file.iter().map(|&v| v + 1).max().unwrap_or(0);
        let mut vertex_source: Vec<usize> = (0..vertices).collect();
        for (file, &v) in vertex_of_file.iter().enumerate().rev() {
            vertex_source[v] = file;
        }
        Self {
            file_faces,
            face_source,
            face_of_file,
            vertex_of_file,
            vertex_source,
        }
    }

    /// Then `next`, a numbering of the mesh this one's mesh became: faces and vertices
    /// traced through both.
    pub(crate) fn then(&self, next: &FileNumbering) -> Self {
        Self::new(
            self.file_faces,
            next.face_source
                .iter()
                .map(|&f| self.face_source[f])
                .collect(),
            self.vertex_of_file
                .iter()
                .map(|&v| next.vertex_of_file[v])
                .collect(),
        )
    }

    /// Faces in the file.
    pub fn file_faces(&self) -> usize {
        self.file_faces
    }

    /// Faces in the mesh read.
    pub fn mesh_faces(&self) -> usize {
        self.face_source.len()
    }

    /// Vertices in the file.
    pub fn file_vertices(&self) -> usize {
        self.vertex_of_file.len()
    }

    /// The file's number of the mesh's face `face`.
    ///
    /// # Panics
    /// If `face` is no face of the mesh.
    pub fn file_face(&self, face: usize) -> usize {
        self.face_source[face]
    }

    /// The file's number of the mesh's vertex `vertex` (the first file vertex joined into
    /// it; a vertex beyond those the file gives keeps its number).
    pub fn file_vertex(&self, vertex: usize) -> usize {
        self.vertex_source.get(vertex).copied().unwrap_or(vertex)
    }

    /// [`Self::file_face`] for a number that may name no face of the mesh (as errors about
    /// a caller's input may): kept as it is then.
    pub fn file_face_or_same(&self, face: usize) -> usize {
        self.face_source.get(face).copied().unwrap_or(face)
    }

    /// The mesh's face that is the file's face `face` (the first of its parts where zipping
    /// split it: only triangle meshes are split, which are never matched face by face).
    ///
    /// # Errors
    /// [`NotInMesh`] when the file has no such face, or reading removed it.
    pub fn mesh_face(&self, face: usize) -> Result<usize, NotInMesh> {
        if face >= self.file_faces {
            return Err(NotInMesh::OutOfRange {
                face,
                file_faces: self.file_faces,
            });
        }
        self.face_of_file[face].ok_or(NotInMesh::Removed { face })
    }

    /// Per face of the mesh, the value `per_file_face` gives its file face.
    ///
    /// # Panics
    /// If `per_file_face` does not have one value per face of the file.
    pub fn faces_from_file<T: Clone>(&self, per_file_face: &[T]) -> Vec<T> {
        assert_eq!(per_file_face.len(), self.file_faces);
        self.face_source
            .iter()
            .map(|&f| per_file_face[f].clone())
            .collect()
    }

    /// Per vertex of the mesh, the value `per_file_vertex` gives the first file vertex that
    /// became it ([`Self::file_vertex`]).
    ///
    /// # Panics
    /// If `per_file_vertex` does not have one value per vertex of the file.
    pub fn vertices_from_file<T: Clone>(&self, per_file_vertex: &[T]) -> Vec<T> {
        assert_eq!(per_file_vertex.len(), self.vertex_of_file.len());
        self.vertex_source
            .iter()
            .map(|&file| per_file_vertex[file].clone())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// File faces 0..5; face 2 removed; file vertices 0..4 with 3 joined to 1.
    fn removed_two() -> FileNumbering {
        FileNumbering::new(5, vec![0, 1, 3, 4], vec![0, 1, 2, 1])
    }

    #[test]
    fn faces_after_a_removed_one_keep_their_file_numbers() {
        let n = removed_two();
        assert_eq!(
            (0..4).map(|f| n.file_face(f)).collect::<Vec<_>>(),
            [0, 1, 3, 4]
        );
        assert_eq!(n.mesh_face(3), Ok(2));
        assert_eq!(n.mesh_face(4), Ok(3));
        assert_eq!(n.mesh_face(2), Err(NotInMesh::Removed { face: 2 }));
        assert_eq!(
            n.mesh_face(5),
            Err(NotInMesh::OutOfRange {
                face: 5,
                file_faces: 5
            })
        );
        assert_eq!(
            n.faces_from_file(&["a", "b", "c", "d", "e"]),
            ["a", "b", "d", "e"]
        );
    }

    #[test]
    fn a_joined_vertex_takes_the_first_file_vertex_value() {
        let n = removed_two();
        assert_eq!(n.vertices_from_file(&[10, 11, 12, 13]), [10, 11, 12]);
        assert_eq!(
            (0..3).map(|v| n.file_vertex(v)).collect::<Vec<_>>(),
            [0, 1, 2]
        );
    }

    #[test]
    fn the_parts_of_a_split_face_take_its_value() {
        // File face 1 split into mesh faces 1 and 3 (zipping appends the parts).
        let n = FileNumbering::new(3, vec![0, 1, 2, 1], vec![0, 1, 2]);
        assert_eq!(n.mesh_face(2), Ok(2));
        assert_eq!(n.mesh_face(1), Ok(1));
        assert_eq!(n.faces_from_file(&[7, 8, 9]), [7, 8, 9, 8]);
    }

    #[test]
    fn then_traces_through_both_readings() {
        let first = removed_two();
        // The second drops mesh face 0 and joins vertex 2 to 0.
        let second = FileNumbering::new(4, vec![1, 2, 3], vec![0, 1, 0]);
        let both = first.then(&second);
        assert_eq!(both.file_face(0), 1);
        assert_eq!(both.file_face(2), 4);
        assert_eq!(both.mesh_face(0), Err(NotInMesh::Removed { face: 0 }));
        assert_eq!(both.vertices_from_file(&[1, 2, 3, 4]), [1, 2]);
    }
}
