//! OFF (Object File Format), read by hand: no maintained crate reads it. A header word
//! (`OFF`, or with the prefixes `ST`, `C`, `N`, `4`, `n` for texture, colour, normals and
//! dimension), the counts of vertices, faces and edges, the vertices (extra numbers after x y
//! z ignored) and the faces as `n i1 ... in` (a colour after them ignored). `#` starts a
//! comment.

use nalgebra::Point3;

use super::Raw;
use crate::mesh::{MAX_FACES, MAX_INDICES, MAX_VERTICES, MeshError};

/// True for the header words of three-dimensional OFF variants.
pub(super) fn is_header(word: &str) -> bool {
    word.strip_suffix("OFF").is_some_and(|prefix| {
        let prefix = prefix.strip_prefix("ST").unwrap_or(prefix);
        let prefix = prefix.strip_prefix('C').unwrap_or(prefix);
        let prefix = prefix.strip_prefix('N').unwrap_or(prefix);
        prefix.is_empty()
    })
}

/// Parses OFF text.
pub(super) fn parse(text: &str) -> Result<Raw, MeshError> {
    let error = |line: usize, message: String| MeshError::Format {
        format: "OFF",
        message: format!("line {line}: {message}"),
    };
    // Words with their line numbers, comments and blank lines left out.
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(n, l)| (n + 1, l.split('#').next().unwrap_or("")))
        .filter(|(_, l)| !l.trim().is_empty());
    let (first, header) = lines
        .next()
        .ok_or_else(|| error(1, "the file is empty".into()))?;
    let mut words = header.split_whitespace();
    let word = words.next().unwrap_or("");
    if !is_header(word) {
        return Err(error(
            first,
            format!("'{word}' is not an OFF header (OFF, COFF, NOFF, STOFF, ...)"),
        ));
    }
    // The counts may follow the header word on its line.
    let mut rest: Vec<&str> = words.collect();
    let mut counts_line = first;
    if rest.is_empty() {
        let (n, l) = lines
            .next()
            .ok_or_else(|| error(first, "the vertex and face counts are missing".into()))?;
        counts_line = n;
        rest = l.split_whitespace().collect();
    }
    let count = |k: usize, what: &str| -> Result<usize, MeshError> {
        let word = rest
            .get(k)
            .ok_or_else(|| error(counts_line, format!("the {what} count is missing")))?;
        word.parse()
            .map_err(|_| error(counts_line, format!("'{word}' is not a {what} count")))
    };
    let (nv, nf) = (count(0, "vertex")?, count(1, "face")?);
    crate::mesh::check_size(nv.min(MAX_VERTICES + 1), nf.min(MAX_FACES + 1), 0)?;
    let mut positions = Vec::with_capacity(nv);
    for k in 0..nv {
        let (n, l) = lines.next().ok_or_else(|| {
            error(
                counts_line,
                format!("the header announces {nv} vertices, the file ends after {k}"),
            )
        })?;
        let mut xyz = [0.0; 3];
        let mut words = l.split_whitespace();
        for c in &mut xyz {
            let word = words
                .next()
                .ok_or_else(|| error(n, "a vertex needs x, y and z".into()))?;
            *c = word
                .parse()
                .map_err(|_| error(n, format!("'{word}' is not a number")))?;
        }
        positions.push(Point3::from(xyz));
    }
    let mut faces = Vec::with_capacity(nf);
    let mut indices = 0usize;
    for k in 0..nf {
        let (n, l) = lines.next().ok_or_else(|| {
            error(
                counts_line,
                format!("the header announces {nf} faces, the file ends after {k}"),
            )
        })?;
        let mut words = l.split_whitespace();
        let size_word = words.next().unwrap_or("");
        let size: usize = size_word
            .parse()
            .map_err(|_| error(n, format!("'{size_word}' is not a face size")))?;
        indices += size;
        if indices > MAX_INDICES {
            return Err(MeshError::TooLarge {
                what: "face indices",
                count: indices,
                limit: MAX_INDICES,
            });
        }
        let face: Result<Vec<usize>, MeshError> = (0..size)
            .map(|_| {
                let word = words.next().ok_or_else(|| {
                    error(n, format!("a face of {size} vertices lists fewer indices"))
                })?;
                word.parse()
                    .map_err(|_| error(n, format!("'{word}' is not a vertex index")))
            })
            .collect();
        faces.push(face?);
    }
    Ok((positions, faces))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_variants_comments_and_colours() {
        let text = "COFF 4 1 0\n# a square\n0 0 0 255 0 0\n1 0 0 255 0 0\n1 1 0 255 0 0\n0 1 0 255 0 0\n4 0 1 2 3 1 0 0\n";
        let (positions, faces) = parse(text).unwrap();
        assert_eq!(positions.len(), 4);
        assert_eq!(faces, vec![vec![0, 1, 2, 3]]);
        assert!(is_header("OFF") && is_header("NOFF") && is_header("STCNOFF"));
        assert!(!is_header("4OFF") && !is_header("OFFSET"));
    }

    #[test]
    fn errors_name_the_line() {
        let short = parse("OFF\n3 1 0\n0 0 0\n1 0 0\n").unwrap_err().to_string();
        assert!(
            short.starts_with("OFF") && short.contains("ends after 2"),
            "{short}"
        );
        let bad = parse("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n")
            .unwrap_err()
            .to_string();
        assert!(bad.contains("line 4") && bad.contains("'x'"), "{bad}");
    }
}
