//! `--field FILE`: the designer's direction field, one vector per input vertex or per input
//! face (which one is decided by the count, see [`UserField::for_mesh`]).
//!
//! Two formats, told apart by the first character that is not white space:
//! - JSON: `[[x, y, z], ...]` or `{"vectors": [[x, y, z], ...]}`;
//! - CSV (or any text): one vector per line as `x,y,z` (commas, semicolons, tabs or spaces
//!   between the numbers); blank lines, lines starting with `#` and a header line whose
//!   fields are not numbers are skipped.

use std::path::Path;

use anyhow::{Context, Result, bail};
use tilepattern::mesh::{FileNumbering, PolyMesh};
use tilepattern::remesh::{FieldSite, RemeshError, UserField};

/// Reads `path` and fits its vectors to `mesh` with the share `weight`. The vectors may be
/// counted against the file `mesh` was read from (`numbering`: welding joins vertices and
/// removes faces) or against `mesh` itself; bad vectors are named by the file's numbers.
pub fn read(
    path: &Path,
    mesh: &PolyMesh,
    numbering: &FileNumbering,
    weight: f64,
) -> Result<UserField> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read the field file {}", path.display()))?;
    let vectors = parse(&text).with_context(|| format!("field file {}", path.display()))?;
    let n = vectors.len();
    // Counted against the mesh, or else against its file (then translated).
    let in_file = !(n == mesh.positions().len() || n == mesh.face_count())
        && (n == numbering.file_vertices() || n == numbering.file_faces());
    let vectors = match in_file {
        true if n == numbering.file_vertices() => numbering.vertices_from_file(&vectors),
        true => numbering.faces_from_file(&vectors),
        false => vectors,
    };
    let field = UserField::for_mesh(mesh, vectors, weight)
        .with_context(|| format!("field file {}", path.display()))?;
    field
        .check(mesh)
        .map_err(|e| {
            if in_file {
                in_file_numbers(e, numbering)
            } else {
                e
            }
        })
        .with_context(|| format!("field file {}", path.display()))?;
    if mesh.positions().len() == mesh.face_count() {
        eprintln!(
            "warning: the mesh has as many vertices as faces ({}); the field file {} is read as one vector per vertex",
            mesh.face_count(),
            path.display()
        );
    }
    Ok(field)
}

/// `error` with a bad vector named by its number in the file (for vectors counted against
/// the file).
fn in_file_numbers(error: RemeshError, numbering: &FileNumbering) -> RemeshError {
    match error {
        RemeshError::BadFieldVector {
            index,
            site,
            vector,
        } => RemeshError::BadFieldVector {
            index: match site {
                FieldSite::Faces => numbering.file_face_or_same(index),
                FieldSite::Vertices => numbering.file_vertex(index),
            },
            site,
            vector,
        },
        other => other,
    }
}

/// The vectors of a field file's text.
pub fn parse(text: &str) -> Result<Vec<[f64; 3]>> {
    match text.trim_start().chars().next() {
        Some('[' | '{') => parse_json(text),
        _ => parse_csv(text),
    }
}

fn parse_json(text: &str) -> Result<Vec<[f64; 3]>> {
    #[derive(serde::Deserialize)]
    #[serde(untagged)]
    enum File {
        Bare(Vec<Vec<f64>>),
        Object { vectors: Vec<Vec<f64>> },
    }
    let file: File = serde_json::from_str(text)
        .context("not a JSON field: write [[x, y, z], ...] or {\"vectors\": [[x, y, z], ...]}")?;
    let (File::Bare(rows) | File::Object { vectors: rows }) = file;
    rows.into_iter()
        .enumerate()
        .map(|(i, row)| match row[..] {
            [x, y, z] => Ok([x, y, z]),
            _ => bail!(
                "vector {i} has {} numbers; every vector is [x, y, z]",
                row.len()
            ),
        })
        .collect()
}

fn parse_csv(text: &str) -> Result<Vec<[f64; 3]>> {
    let mut vectors = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let numbers: Option<Vec<f64>> = fields.iter().map(|f| f.parse().ok()).collect();
        match numbers.as_deref() {
            Some(&[x, y, z]) => vectors.push([x, y, z]),
            // A header (x,y,z or vx,vy,vz) before the first vector.
            None if vectors.is_empty() && fields.iter().all(|f| f.parse::<f64>().is_err()) => {}
            _ => bail!(
                "line {}: '{line}' is not a vector; write x,y,z (one vector per vertex or per face)",
                number + 1
            ),
        }
    }
    if vectors.is_empty() {
        bail!("no vectors found; write one x,y,z line per vertex or per face");
    }
    Ok(vectors)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_with_a_header_comments_and_mixed_separators() {
        let text = "# stresses\nvx,vy,vz\n1,0,0\n\n0.5; 0.5; 0\n0\t1\t2\n-1e-3 2 3\n";
        let v = parse(text).unwrap();
        assert_eq!(
            v,
            vec![
                [1.0, 0.0, 0.0],
                [0.5, 0.5, 0.0],
                [0.0, 1.0, 2.0],
                [-1e-3, 2.0, 3.0]
            ]
        );
    }

    #[test]
    fn csv_errors_name_the_line() {
        let err = parse("1,0,0\n1,0\n").unwrap_err().to_string();
        assert!(err.contains("line 2"), "{err}");
        let err = parse("1,0,0\nx,y,z\n").unwrap_err().to_string();
        assert!(err.contains("line 2"), "{err}");
        assert!(parse("# nothing\n").is_err());
    }

    #[test]
    fn json_bare_and_in_an_object() {
        assert_eq!(
            parse("[[1,2,3],[4,5,6]]").unwrap(),
            vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]]
        );
        assert_eq!(
            parse(" {\"vectors\": [[0,0,1]]}").unwrap(),
            vec![[0.0, 0.0, 1.0]]
        );
        let err = format!("{:#}", parse("[[1,2,3],[4,5]]").unwrap_err());
        assert!(err.contains("vector 1"), "{err}");
        assert!(parse("[1,2,3]").is_err());
    }
}
