use thiserror::Error;

/// Why a mesh was refused. Every variant names the face or vertex (0-based) at fault, so a
/// designer can find it in Rhino or in the OBJ file.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum MeshError {
    /// The mesh has no faces or no vertices.
    #[error("the mesh is empty ({vertices} vertices, {faces} faces): give at least one face")]
    Empty {
        /// Number of vertices given.
        vertices: usize,
        /// Number of faces given.
        faces: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error(
        "vertex {vertex} has a NaN or infinite coordinate; fix or delete that vertex (an export gone wrong: export the mesh again)"
    )]
    NonFiniteCoordinate {
        /// The vertex at fault.
        vertex: usize,
    },
    /// A coordinate is larger in magnitude than [`super::MAX_COORDINATE`].
    #[error(
        "vertex {vertex} has a coordinate of magnitude {value:e}; coordinates may be at most {limit:e} (wrong units?)"
    )]
    CoordinateTooLarge {
        /// The vertex at fault.
        vertex: usize,
        /// The largest magnitude among its coordinates.
        value: f64,
        /// The limit.
        limit: f64,
    },
    /// A face has fewer than three vertices.
    #[error(
        "face {face} has {count} vertices; a face needs at least 3: delete that face (Rhino: CullDegenerateMeshFaces)"
    )]
    TooFewVertices {
        /// The face at fault.
        face: usize,
        /// How many vertices it has.
        count: usize,
    },
    /// A face refers to a vertex that does not exist.
    #[error(
        "face {face} refers to vertex {index}, but the mesh has only {vertex_count} vertices (counted from 0: the last is {})", vertex_count.saturating_sub(1)
    )]
    IndexOutOfRange {
        /// The face at fault.
        face: usize,
        /// The bad index.
        index: usize,
        /// Number of vertices in the mesh.
        vertex_count: usize,
    },
    /// A face lists the same vertex twice.
    #[error(
        "face {face} uses vertex {vertex} more than once; delete that face or give it its distinct corners (Rhino: CullDegenerateMeshFaces)"
    )]
    RepeatedIndex {
        /// The face at fault.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// An edge is shared by more than two faces.
    #[error(
        "edge {a}-{b} is shared by {face_count} faces (faces {faces:?}); a surface edge may border at most 2 faces: a fin, a wall or a second shell meets the surface there, so delete those faces or tile each part as a mesh of its own (Rhino: ExtractNonManifoldMeshEdges shows them)"
    )]
    NonManifoldEdge {
        /// First vertex of the edge.
        a: usize,
        /// Second vertex of the edge.
        b: usize,
        /// How many faces share it.
        face_count: usize,
        /// The first three faces found on it.
        faces: Vec<usize>,
    },
    /// A face without area (its corners on a line) lies along an edge of two other faces, a
    /// third face there: exporters leave such slivers where they closed a gap.
    #[error(
        "face {face} has no area (its corners lie on a line) and lies along edge {a}-{b} of two other faces; delete degenerate faces (Rhino: CullDegenerateMeshFaces) and read the mesh again"
    )]
    DegenerateFace {
        /// The face without area.
        face: usize,
        /// First vertex of the edge.
        a: usize,
        /// Second vertex of the edge.
        b: usize,
    },
    /// Two faces have the same vertices.
    #[error("face {face} repeats face {first} (the same vertices); remove one of them")]
    DuplicateFace {
        /// The later face.
        face: usize,
        /// The face it repeats.
        first: usize,
    },
    /// Two faces run along their shared edge in the same direction: their normals point to
    /// opposite sides.
    #[error(
        "faces {faces:?} both run from vertex {a} to vertex {b}: their orientations disagree; unify the face normals (Rhino: UnifyMeshNormals)"
    )]
    InconsistentOrientation {
        /// Start of the shared edge in both faces.
        a: usize,
        /// End of the shared edge in both faces.
        b: usize,
        /// The two faces.
        faces: [usize; 2],
    },
    /// The surface is one-sided (a Möbius strip): no choice of sides makes every pair of
    /// neighbouring faces agree.
    #[error(
        "the surface is one-sided, like a Moebius strip: going round from face {} to face {} turns it over, so no side can be the top the tiles lie on; cut the surface open across its twist and tile the parts",
        .faces[0],
        .faces[1]
    )]
    NonOrientable {
        /// Two neighbouring faces that cannot agree once the others are turned to match.
        faces: [usize; 2],
    },
    /// The mesh is larger than one call may take.
    #[error(
        "the mesh has {count} {what}; one call takes at most {limit}: split the shell into parts"
    )]
    TooLarge {
        /// `"vertices"`, `"faces"` or `"face indices"`.
        what: &'static str,
        /// How many were given.
        count: usize,
        /// The limit.
        limit: usize,
    },
    /// The OBJ text could not be read.
    #[error("OBJ line {line}: {message}")]
    ObjSyntax {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// A file could not be read as the format it was taken for (or as any format).
    #[error("{format}: {message}")]
    Format {
        /// The format's name (`"binary STL"`, `"ASCII PLY"`, `"OFF"`, ...).
        format: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The file could not be read or written.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
}

impl MeshError {
    /// The error with its faces and vertices numbered as in the file `numbering` traces
    /// (errors found after welding, when reading removed faces or joined vertices).
    pub fn in_file_numbers(self, numbering: &super::FileNumbering) -> Self {
        let f = |face: usize| numbering.file_face_or_same(face);
        let v = |vertex: usize| numbering.file_vertex(vertex);
        match self {
            MeshError::NonFiniteCoordinate { vertex } => {
                MeshError::NonFiniteCoordinate { vertex: v(vertex) }
            }
            MeshError::CoordinateTooLarge {
                vertex,
                value,
                limit,
            } => MeshError::CoordinateTooLarge {
                vertex: v(vertex),
                value,
                limit,
            },
            MeshError::TooFewVertices { face, count } => MeshError::TooFewVertices {
                face: f(face),
                count,
            },
            MeshError::RepeatedIndex { face, vertex } => MeshError::RepeatedIndex {
                face: f(face),
                vertex: v(vertex),
            },
            MeshError::NonManifoldEdge {
                a,
                b,
                face_count,
                faces,
            } => MeshError::NonManifoldEdge {
                a: v(a),
                b: v(b),
                face_count,
                faces: faces.into_iter().map(f).collect(),
            },
            MeshError::DegenerateFace { face, a, b } => MeshError::DegenerateFace {
                face: f(face),
                a: v(a),
                b: v(b),
            },
            MeshError::DuplicateFace { face, first } => MeshError::DuplicateFace {
                face: f(face),
                first: f(first),
            },
            MeshError::InconsistentOrientation { a, b, faces } => {
                MeshError::InconsistentOrientation {
                    a: v(a),
                    b: v(b),
                    faces: faces.map(f),
                }
            }
            MeshError::NonOrientable { faces } => MeshError::NonOrientable {
                faces: faces.map(f),
            },
            // An index out of range is left as it was: welding leaves such meshes as read.
            other => other,
        }
    }
}
