use thiserror::Error;

/// Why the pattern stage could not run.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PatternError {
    /// A bond weight is negative, NaN or infinite.
    #[error("bond weight {weight:?} is not a finite number >= 0")]
    InvalidWeight {
        /// The weight given.
        weight: f64,
    },
    /// A bond weight is larger than [`super::MAX_WEIGHT`]: it would only break the solver's
    /// numerics.
    #[error(
        "bond weight {weight:?} is larger than {max}, the most that makes sense (above 1 one joint already outweighs a tile)"
    )]
    WeightTooLarge {
        /// The weight given.
        weight: f64,
        /// The largest weight accepted.
        max: f64,
    },
    /// A face index in the options does not exist.
    #[error(
        "face {face} does not exist (the mesh has {face_count} faces, counted from 0: the last is {})",
        face_count.saturating_sub(1)
    )]
    FaceOutOfRange {
        /// The index given.
        face: usize,
        /// Number of faces in the mesh.
        face_count: usize,
    },
    /// A forced pair names two faces that do not share an edge.
    #[error("forced pair [{a}, {b}]: the faces do not share an edge, so they cannot form one tile")]
    ForcedNotAdjacent {
        /// First face.
        a: usize,
        /// Second face.
        b: usize,
    },
    /// A face appears in two forced pairs.
    #[error("face {face} appears in more than one forced pair")]
    ForcedTwice {
        /// The face at fault.
        face: usize,
    },
    /// A forced pair uses an excluded face.
    #[error("face {face} is both excluded and in a forced pair")]
    ForcedExcluded {
        /// The face at fault.
        face: usize,
    },
    /// A forced pair uses a face that is not a quad.
    #[error("face {face} has {corners} corners; only quads can be paired into a tile")]
    ForcedNonQuad {
        /// The face at fault.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
    /// The time limit is negative, NaN or infinite.
    #[error("time limit {seconds:?} s is not a finite number >= 0")]
    InvalidTimeLimit {
        /// The limit given.
        seconds: f64,
    },
    /// The relative gap to stop at is not a number from 0 to 1.
    #[error(
        "relative gap {gap:?} is not a number from 0 to 1 (0 proves optimality, 0.01 stops within 1 %)"
    )]
    InvalidGap {
        /// The gap given.
        gap: f64,
    },
    /// The up direction of level courses is not a finite non-zero vector.
    #[error("courses up direction {up:?} is not a finite non-zero vector")]
    InvalidUp {
        /// The direction given.
        up: [f64; 3],
    },
    /// A forced pair lies across two courses when tiles are laid in courses.
    #[error(
        "forced pair [{a}, {b}]: the faces lie in two courses (their shared edge runs along the courses), so in courses they cannot form one tile; force pairs along a course or lay tiles either way"
    )]
    ForcedAcrossCourses {
        /// First face.
        a: usize,
        /// Second face.
        b: usize,
    },
    /// A bond that lays tiles both ways (herringbone, basket weave) was asked for with tiles
    /// in level courses, where every tile runs along the courses.
    #[error(
        "the {bond} bond lays tiles both ways, but in level courses every tile runs along the courses; lay tiles either way (courses free)"
    )]
    BondAcrossCourses {
        /// The bond's name.
        bond: &'static str,
    },
    /// The zones do not give one bond per face.
    #[error(
        "zones give {given} bonds for a mesh of {faces} faces; give one bond per face, in face order"
    )]
    ZoneCount {
        /// Bonds given.
        given: usize,
        /// Faces of the mesh.
        faces: usize,
    },
    /// The bond of a zone is not valid (its weight).
    #[error("zone of face {face}: {reason}")]
    InvalidZone {
        /// The first face at fault.
        face: usize,
        /// What is wrong with its bond.
        reason: String,
    },
    /// The caller cancelled the stage through its [`crate::control::Control`].
    #[error("cancelled by the caller")]
    Cancelled,
    /// CBC failed.
    #[error("the MIP solver failed: {0}")]
    Solver(String),
}

impl PatternError {
    /// The error with the faces it names numbered as in the file `numbering` traces (the
    /// caller's own numbers, where reading removed faces).
    pub fn in_file_numbers(self, numbering: &crate::mesh::FileNumbering) -> Self {
        let f = |face: usize| numbering.file_face_or_same(face);
        match self {
            PatternError::ForcedNotAdjacent { a, b } => {
                PatternError::ForcedNotAdjacent { a: f(a), b: f(b) }
            }
            PatternError::ForcedAcrossCourses { a, b } => {
                PatternError::ForcedAcrossCourses { a: f(a), b: f(b) }
            }
            PatternError::ForcedTwice { face } => PatternError::ForcedTwice { face: f(face) },
            PatternError::ForcedExcluded { face } => PatternError::ForcedExcluded { face: f(face) },
            PatternError::ForcedNonQuad { face, corners } => PatternError::ForcedNonQuad {
                face: f(face),
                corners,
            },
            PatternError::InvalidZone { face, reason } => PatternError::InvalidZone {
                face: f(face),
                reason,
            },
            other => other,
        }
    }
}
