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

/// The mesh's faces of the pair of file faces `[a, b]`, given by `what` (e.g. "--force").
pub fn mesh_pair(numbering: &FileNumbering, [a, b]: [usize; 2], what: &str) -> Result<[usize; 2]> {
    let both = mesh_faces(numbering, &[a, b], &format!("{what} {a},{b}"))?;
    Ok([both[0], both[1]])
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
        excluded: in_file(&pattern.excluded, numbering),
        non_quad: in_file(&pattern.non_quad, numbering),
        ..pattern.clone()
    }
}

/// `faces` of the mesh as the file's faces, sorted, each once (the parts of a triangle that
/// zipping split are one face of the file).
fn in_file(faces: &[usize], numbering: &FileNumbering) -> Vec<usize> {
    let mut file: Vec<usize> = faces.iter().map(|&f| numbering.file_face(f)).collect();
    file.sort_unstable();
    file.dedup();
    file
}

/// A pattern read from `match`'s JSON (faces numbered as in the file) with the faces of the
/// mesh read from that file.
///
/// A pattern counting the welded mesh's faces (as `match` wrote them before its numbers
/// were the file's) is read as it is, with a warning, and so is one of another face count,
/// for the pipeline to refuse once it has checked the options.
///
/// # Errors
/// When it names a face the file does not have, or one reading removed.
pub fn pattern_from_file(pattern: Pattern, numbering: &FileNumbering) -> Result<Pattern> {
    let (file, mesh) = (numbering.file_faces(), numbering.mesh_faces());
    if pattern.faces != file {
        // Written by `match` before its numbers were the file's (2026-12-07); any other
        // count is another mesh's pattern, which the pipeline names after the options.
        if pattern.faces == mesh {
            eprintln!(
                "warning: the pattern counts {mesh} faces, as many as the mesh has once read, not the {file} of its file: its face numbers are read as counted after welding, as `match` wrote them before its numbers were the file's; run `match` again to have them in the file's numbers"
            );
        }
        return Ok(pattern);
    }
    let mesh = |list: &[usize], what: &str| mesh_faces(numbering, list, what);
    let pairs = pattern
        .pairs
        .iter()
        .map(|&p| mesh_pair(numbering, p, "pair"))
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
