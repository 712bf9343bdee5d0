//! Face numbers as the file has them. Reading can remove faces (welding collapses them, or
//! one repeats another), which renumbers the faces after them in the mesh the library
//! sees; on the command line every face number (`--force`, `--exclude`, `--zones`, a per-face
//! `--field`, `match`'s JSON, `tiles`' sequence.json) is the file's, translated here.

use anyhow::{Context, Result};
use tilepattern::mesh::FileNumbering;
use tilepattern::pattern::Pattern;

/// The mesh's faces for the file's faces `faces`, given by `what` (e.g. "--exclude").
pub fn mesh_faces(numbering: &FileNumbering, faces: &[usize], what: &str) -> Result<Vec<usize>> {
    faces
        .iter()
        .map(|&f| numbering.mesh_face(f).with_context(|| what.to_owned()))
        .collect()
}

/// `pattern` (of the mesh) with its faces numbered as in the file; `faces` is then the
/// file's count.
pub fn pattern_in_file(pattern: &Pattern, numbering: &FileNumbering) -> Pattern {
    let file = |f: &usize| numbering.file_face(*f);
    Pattern {
        faces: numbering.file_faces(),
        // Reading keeps the file's order of quads, so pairs stay sorted with a < b.
        pairs: pattern
            .pairs
            .iter()
            .map(|p| p.each_ref().map(file))
            .collect(),
        unpaired: pattern.unpaired.iter().map(file).collect(),
        excluded: pattern.excluded.iter().map(file).collect(),
        non_quad: pattern.non_quad.iter().map(file).collect(),
        ..pattern.clone()
    }
}

/// A pattern read from `match`'s JSON (faces numbered as in the file) with the faces of the
/// mesh read from that file.
///
/// # Errors
/// When it was made for a file of another face count, or names a face reading removed.
pub fn pattern_from_file(pattern: Pattern, numbering: &FileNumbering) -> Result<Pattern> {
    if pattern.faces != numbering.file_faces() {
        // The pipeline names the mismatch against the mesh.
        return Ok(pattern);
    }
    let mesh = |list: &[usize], what: &str| mesh_faces(numbering, list, what);
    let pairs = pattern
        .pairs
        .iter()
        .map(|&[a, b]| {
            let both = mesh(&[a, b], &format!("pair [{a}, {b}]"))?;
            Ok([both[0], both[1]])
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Pattern {
        faces: numbering.mesh_faces(),
        pairs,
        unpaired: mesh(&pattern.unpaired, "unpaired")?,
        excluded: mesh(&pattern.excluded, "excluded")?,
        non_quad: mesh(&pattern.non_quad, "non_quad")?,
        ..pattern
    })
}
