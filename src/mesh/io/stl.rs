//! STL through the `stl_io` crate: ASCII and binary, every triangle with its own three corners
//! (the caller welds them).

use std::io::Cursor;

use nalgebra::Point3;

use super::{Format, Raw};
use crate::mesh::{MAX_FACES, MeshError};

/// Bytes of a binary STL's header and triangle count, and of one triangle.
const HEADER: usize = 84;
const TRIANGLE: usize = 50;

/// True when `bytes` is exactly as long as the binary STL its triangle count announces. This
/// tells binary from ASCII even when a binary header starts with `solid`, as many exporters
/// write it.
pub(super) fn is_binary(bytes: &[u8]) -> bool {
    announced(bytes).is_some_and(|n| {
        Some(bytes.len()) == n.checked_mul(TRIANGLE).and_then(|b| b.checked_add(HEADER))
    })
}

/// The triangle count in a binary STL header.
fn announced(bytes: &[u8]) -> Option<usize> {
    let count: [u8; 4] = bytes.get(80..84)?.try_into().ok()?;
    Some(u32::from_le_bytes(count) as usize)
}

/// Parses an STL file of the given flavour.
pub(super) fn parse(bytes: &[u8], format: Format) -> Result<Raw, MeshError> {
    let error = |message: String| MeshError::Format {
        format: format.name(),
        message,
    };
    let mut owned;
    let bytes = if format == Format::StlBinary {
        let Some(count) = announced(bytes) else {
            return Err(error(format!(
                "the file has {} bytes, fewer than the {HEADER} of a binary STL's header",
                bytes.len()
            )));
        };
        // The size first: a corrupt count is no reason to call the shell too large.
        if !is_binary(bytes) {
            let expected = HEADER as u64 + TRIANGLE as u64 * count as u64;
            let why = if (bytes.len() as u64) < expected {
                "the file is cut short or not an STL"
            } else {
                "the header's count is wrong or data was appended; export the STL again"
            };
            return Err(error(format!(
                "the header announces {count} triangles ({expected} bytes), but the file has {} bytes: {why}",
                bytes.len()
            )));
        }
        if count > MAX_FACES {
            return Err(MeshError::TooLarge {
                what: "faces",
                count,
                limit: MAX_FACES,
            });
        }
        // `stl_io` takes a header starting with "solid " for ASCII; the size proved binary.
        owned = bytes.to_vec();
        owned[..5].fill(b' ');
        &owned[..]
    } else {
        owned = ascii_for_the_reader(bytes.trim_ascii_start());
        &owned[..]
    };
    let mut cursor = Cursor::new(bytes);
    let reader = stl_io::create_stl_reader(&mut cursor).map_err(|e| error(e.to_string()))?;
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for (k, triangle) in reader.enumerate() {
        let triangle = triangle.map_err(|e| error(format!("triangle {k}: {e}")))?;
        if faces.len() >= MAX_FACES {
            return Err(MeshError::TooLarge {
                what: "faces",
                count: faces.len() + 1,
                limit: MAX_FACES,
            });
        }
        let first = positions.len();
        positions.extend(
            triangle
                .vertices
                .iter()
                .map(|v| Point3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2]))),
        );
        faces.push(vec![first, first + 1, first + 2]);
    }
    Ok((positions, faces))
}

/// An ASCII STL as `stl_io` reads it: one solid (exporters write one per object, and the
/// reader stopped at the first `endsolid`, leaving the rest of the file out without a word),
/// opened by "solid " and a name (some exporters write "solid" alone), keywords in lower case
/// (some write them in upper case), and every facet normal zero, since the corners alone give
/// the triangle and exporters write "nan" for a degenerate facet's normal, which failed the
/// whole file.
fn ascii_for_the_reader(text: &[u8]) -> Vec<u8> {
    let text = text.to_ascii_lowercase();
    let mut out = Vec::with_capacity(text.len() + 16);
    out.extend_from_slice(b"solid merged\n");
    // Within a solid (from its `solid` line to its `endsolid`, or the end of the file):
    // text after the last solid, as some exporters leave, is no facet.
    let mut within = false;
    for line in text.split_inclusive(|&b| b == b'\n') {
        let words: Vec<&[u8]> = line
            .split(u8::is_ascii_whitespace)
            .filter(|w| !w.is_empty())
            .collect();
        match words.first().copied() {
            Some(b"solid") => within = true,
            Some(b"endsolid") => within = false,
            _ if !within => {}
            Some(b"facet") if words.len() == 5 && words[1] == b"normal" => {
                out.extend_from_slice(b"facet normal 0 0 0\n");
            }
            _ => out.extend_from_slice(line),
        }
    }
    if out.last() != Some(&b'\n') {
        out.push(b'\n');
    }
    out.extend_from_slice(b"endsolid merged\n");
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A binary STL of the given triangles, its header starting with "solid" as some
    /// exporters write it.
    pub(crate) fn binary(triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = b"solid exported".to_vec();
        bytes.resize(80, 0);
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            for c in t.iter().flatten() {
                bytes.extend(c.to_le_bytes());
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    #[test]
    fn binary_with_a_solid_header_is_binary() {
        let bytes = binary(&[[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]]);
        assert!(is_binary(&bytes));
        let (positions, faces) = parse(&bytes, Format::StlBinary).unwrap();
        assert_eq!(positions.len(), 3);
        assert_eq!(faces, vec![vec![0, 1, 2]]);
        let cut = parse(&bytes[..100], Format::StlBinary)
            .unwrap_err()
            .to_string();
        assert!(
            cut.starts_with("binary STL") && cut.contains("cut short"),
            "{cut}"
        );
        // A count far beyond the file's size is a corrupt file, not a shell too large.
        let mut huge = bytes.clone();
        huge[80..84].copy_from_slice(&1_000_000_000u32.to_le_bytes());
        let corrupt = parse(&huge, Format::StlBinary).unwrap_err().to_string();
        assert!(corrupt.contains("cut short"), "{corrupt}");
    }

    #[test]
    fn ascii_reads_and_names_its_errors() {
        let text = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
        let (positions, faces) = parse(text.as_bytes(), Format::StlAscii).unwrap();
        assert_eq!((positions.len(), faces.len()), (3, 1));
        let unnamed = text.replacen("solid s\n", "  solid\r\n", 1);
        let (positions, faces) = parse(unnamed.as_bytes(), Format::StlAscii).unwrap();
        assert_eq!((positions.len(), faces.len()), (3, 1));
        let bad = text.replace("vertex 1 0 0", "vertex 1 zero 0");
        let error = parse(bad.as_bytes(), Format::StlAscii)
            .unwrap_err()
            .to_string();
        assert!(error.starts_with("ASCII STL"), "{error}");
        // A degenerate facet's normal written as "nan" (before: the whole file refused).
        let nan = text.replace("facet normal 0 0 1", "facet normal nan nan nan");
        let (positions, faces) = parse(nan.as_bytes(), Format::StlAscii).unwrap();
        assert_eq!((positions.len(), faces.len()), (3, 1));
    }

    #[test]
    fn every_solid_of_an_ascii_stl_is_read_whatever_the_case_and_the_trailing_text() {
        let text = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n";
        // Two solids (before: the second left out without a word), then text after them.
        let two = format!("{text}{}end of export\n", text.replace(" 0 0\n", " 0 5\n"));
        let (positions, faces) = parse(two.as_bytes(), Format::StlAscii).unwrap();
        assert_eq!((positions.len(), faces.len()), (6, 2));
        assert!(positions.iter().any(|p| p.z == 5.0));
        // Keywords in upper case, as some exporters write them, detected and read as ASCII.
        let upper = text.to_ascii_uppercase();
        assert_eq!(
            super::super::detect(upper.as_bytes(), Some("stl")).unwrap(),
            Format::StlAscii
        );
        let (positions, faces) = parse(upper.as_bytes(), Format::StlAscii).unwrap();
        assert_eq!((positions.len(), faces.len()), (3, 1));
    }
}
