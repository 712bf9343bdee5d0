//! Wavefront OBJ in and out.
//!
//! Only geometry is read: `v` lines and `f` lines (`v`, `v/vt`, `v//vn`, `v/vt/vn`). Negative
//! indices are legal OBJ and are accepted: `-1` is the last vertex read so far, `-2` the one
//! before it, and so on; a negative index reaching before the first vertex, and index 0, are
//! [`MeshError::ObjSyntax`] errors naming the line. Vertex and face order are kept exactly as
//! in the file, which is why this is not `tobj`: it renumbers vertices by first use and splits
//! groups into separate meshes, and face indices in our results must refer to the file's own
//! numbering (0-based: the first `f` line is face 0, the first `v` line vertex 0).

use std::fmt::Write as _;
use std::path::Path;

use nalgebra::Point3;

use super::{MAX_FACES, MAX_INDICES, MAX_VERTICES, MeshError, PolyMesh};

/// Largest OBJ file [`read`] loads: a mesh at the size limits ([`MAX_VERTICES`],
/// [`MAX_FACES`], [`MAX_INDICES`]) takes well under a gigabyte of OBJ text.
pub const MAX_FILE_BYTES: u64 = 2 << 30;

/// Parses OBJ text into a validated mesh.
///
/// # Errors
/// [`MeshError::ObjSyntax`] with the line number for malformed lines,
/// [`MeshError::TooLarge`] as soon as the text holds more vertices, faces or face indices
/// than one mesh may have, then any validation error of [`PolyMesh::new`].
pub fn parse(text: &str) -> Result<PolyMesh, MeshError> {
    let (positions, faces) = parse_raw(text)?;
    PolyMesh::new(positions, faces)
}

/// Parses OBJ text into positions and faces without validating them (for [`super::io`],
/// which may weld them first).
///
/// # Errors
/// As [`parse`], but no validation error.
/// The lines of an OBJ text with a line ending in a backslash joined to the next (the
/// format's line continuation), each with the number of its first line (from 1).
fn logical_lines(text: &str) -> impl Iterator<Item = (usize, std::borrow::Cow<'_, str>)> {
    let mut lines = text.lines().enumerate();
    std::iter::from_fn(move || {
        let (number, raw) = lines.next()?;
        let Some(head) = raw.trim_end().strip_suffix('\\') else {
            return Some((number + 1, raw.into()));
        };
        let mut joined = format!("{head} ");
        for (_, next) in lines.by_ref() {
            match next.trim_end().strip_suffix('\\') {
                Some(more) => {
                    joined.push_str(more);
                    joined.push(' ');
                }
                None => {
                    joined.push_str(next);
                    break;
                }
            }
        }
        Some((number + 1, joined.into()))
    })
}

pub(crate) fn parse_raw(text: &str) -> Result<super::io::Raw, MeshError> {
    let mut positions = Vec::new();
    let mut faces: Vec<Vec<usize>> = Vec::new();
    let mut index_count = 0usize;
    // Free-form geometry (NURBS surfaces and curves, as Rhino exports a surface to OBJ when
    // not asked for a mesh): not read, but named when it is all the file holds.
    let mut free_form = 0usize;
    for (line, raw) in logical_lines(text) {
        let syntax = |message: String| MeshError::ObjSyntax { line, message };
        let content = raw.split('#').next().unwrap_or("");
        let mut words = content.split_whitespace();
        match words.next() {
            Some("v") => {
                let mut xyz = [0.0; 3];
                for c in &mut xyz {
                    let word = words
                        .next()
                        .ok_or_else(|| syntax("a vertex needs x, y and z".into()))?;
                    *c = word
                        .parse()
                        .map_err(|_| syntax(format!("'{word}' is not a number")))?;
                }
                positions.push(Point3::from(xyz));
                if positions.len() > MAX_VERTICES {
                    return Err(MeshError::TooLarge {
                        what: "vertices",
                        count: positions.len(),
                        limit: MAX_VERTICES,
                    });
                }
            }
            // `fo` is the old name of a face.
            Some("f" | "fo") => {
                let mut face = Vec::new();
                for word in words {
                    let first = word.split('/').next().unwrap_or("");
                    let index: i64 = first
                        .parse()
                        .map_err(|_| syntax(format!("'{word}' is not a vertex reference")))?;
                    let resolved = match index {
                        i if i > 0 => i - 1,
                        i if i < 0 => positions.len() as i64 + i,
                        _ => {
                            return Err(syntax(
                                "vertex index 0 is not valid in OBJ (indices start at 1)".into(),
                            ));
                        }
                    };
                    let resolved = usize::try_from(resolved).map_err(|_| {
                        syntax(format!(
                            "relative index {index} reaches before the first vertex"
                        ))
                    })?;
                    face.push(resolved);
                    index_count += 1;
                    if index_count > MAX_INDICES {
                        return Err(MeshError::TooLarge {
                            what: "face indices",
                            count: index_count,
                            limit: MAX_INDICES,
                        });
                    }
                }
                faces.push(face);
                if faces.len() > MAX_FACES {
                    return Err(MeshError::TooLarge {
                        what: "faces",
                        count: faces.len(),
                        limit: MAX_FACES,
                    });
                }
            }
            Some("surf" | "curv" | "curv2" | "cstype") => free_form += 1,
            _ => {}
        }
    }
    if faces.is_empty() && free_form > 0 {
        return Err(MeshError::Format {
            format: "OBJ",
            message: format!(
                "the file holds free-form geometry ({free_form} surf, curv or cstype statements, NURBS as Rhino writes a surface) and no mesh faces: export the surface as a mesh (Rhino: Mesh the surface, or in the OBJ export options choose Geometry: Mesh)"
            ),
        });
    }
    Ok((positions, faces))
}

/// Reads and validates an OBJ file.
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read or is larger than [`MAX_FILE_BYTES`],
/// otherwise as [`parse`].
pub fn read(path: &Path) -> Result<PolyMesh, MeshError> {
    let size = std::fs::metadata(path)
        .map_err(|e| io_error(path, &e))?
        .len();
    if size > MAX_FILE_BYTES {
        let message = format!(
            "the file has {size} bytes; an OBJ file may have at most {MAX_FILE_BYTES} (split the shell into parts)"
        );
        return Err(MeshError::Io {
            path: path.display().to_string(),
            message,
        });
    }
    let text = std::fs::read_to_string(path).map_err(|e| io_error(path, &e))?;
    parse(&text)
}

/// Formats a mesh as OBJ text (1-based indices, full precision so a round trip is exact).
pub fn to_string(mesh: &PolyMesh) -> String {
    let mut out = String::new();
    for p in mesh.positions() {
        let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
    }
    for face in mesh.faces() {
        out.push('f');
        for v in face {
            let _ = write!(out, " {}", v + 1);
        }
        out.push('\n');
    }
    out
}

/// Writes a mesh as an OBJ file.
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be written.
pub fn write(mesh: &PolyMesh, path: &Path) -> Result<(), MeshError> {
    std::fs::write(path, to_string(mesh)).map_err(|e| io_error(path, &e))
}

pub(crate) fn io_error(path: &Path, e: &std::io::Error) -> MeshError {
    MeshError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}
