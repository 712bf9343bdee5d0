//! PLY through the `ply-rs-bw` crate (the maintained fork of `ply-rs`): ASCII and binary
//! (either byte order), the `vertex` element's `x`, `y`, `z` and the `face` element's
//! `vertex_indices` (or `vertex_index`) lists; other elements and properties are ignored.

use std::io::Cursor;

use nalgebra::Point3;
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{
    DefaultElement, ElementDef, Encoding, Header, Payload, Property, PropertyType, ScalarType,
};

use super::{Format, Raw};
use crate::mesh::MeshError;

/// ASCII or binary PLY, from the header's `format` line.
pub(super) fn encoding(bytes: &[u8]) -> Format {
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(1024)]);
    let binary = head
        .lines()
        .take_while(|l| l.trim() != "end_header")
        .any(|l| l.trim_start().starts_with("format binary"));
    if binary {
        Format::PlyBinary
    } else {
        Format::PlyAscii
    }
}

/// Parses a PLY file.
pub(super) fn parse(bytes: &[u8], format: Format) -> Result<Raw, MeshError> {
    let error = |message: String| MeshError::Format {
        format: format.name(),
        message,
    };
    let parser = Parser::<DefaultElement>::new();
    let header = parser
        .read_ply_header(&mut Cursor::new(bytes))
        .map_err(|e| error(format!("header: {e}")))?;
    let format = match header.encoding {
        Encoding::Ascii => Format::PlyAscii,
        _ => Format::PlyBinary,
    };
    let error = |message: String| MeshError::Format {
        format: format.name(),
        message,
    };
    let count = |name: &str| header.elements.get(name).map_or(0, |e| e.count);
    // The data after the header's last line.
    let body = bytes
        .windows(10)
        .position(|w| w == b"end_header")
        .map(|at| {
            let line = bytes[at..]
                .iter()
                .position(|&b| b == b'\n')
                .map_or(0, |n| n + 1);
            &bytes[at + line..]
        })
        .unwrap_or_default();
    // The counts must fit the file: a corrupt header is no shell too large.
    let least: u128 = header
        .elements
        .values()
        .map(|e| e.count as u128 * least_bytes(e, header.encoding == Encoding::Ascii))
        .sum();
    if least > body.len() as u128 {
        return Err(error(format!(
            "the header announces {} vertices and {} faces, at least {least} bytes, but {} bytes follow it: the file is cut short or corrupt",
            count("vertex"),
            count("face"),
            body.len()
        )));
    }
    crate::mesh::check_size(count("vertex"), count("face"), 0)?;
    let face_list = header.elements.get("face").and_then(|e| {
        ["vertex_indices", "vertex_index"]
            .into_iter()
            .find(|k| e.properties.contains_key(*k))
    });
    if count("face") > 0 && face_list.is_none() {
        return Err(error("the face element has no vertex_indices list".into()));
    }
    let ply = parser
        .read_ply(&mut Cursor::new(bytes))
        .map_err(|e| error(e.to_string()))?;
    // Data after the last element the header announces: a header whose counts are short,
    // which left the rest of the shell out without a word.
    let beyond = if header.encoding == Encoding::Ascii {
        // One record a line.
        let records: usize = header.elements.values().map(|e| e.count).sum();
        let lines = body
            .split(|&b| b == b'\n')
            .filter(|l| !l.trim_ascii().is_empty());
        let extra = lines.count().saturating_sub(records);
        (extra > 0).then(|| format!("{extra} lines"))
    } else {
        let rest = body
            .get(binary_bytes(&header, &ply.payload)..)
            .unwrap_or_default();
        (!rest.trim_ascii().is_empty()).then(|| format!("{} bytes", rest.len()))
    };
    if let Some(beyond) = beyond {
        return Err(error(format!(
            "{beyond} follow the {} vertices and {} faces the header announces: its counts are short of what the file holds, so part of the shell would be left out; export the PLY again",
            count("vertex"),
            count("face")
        )));
    }
    let empty = Vec::new();
    let vertices = ply.payload.get("vertex").unwrap_or(&empty);
    let mut positions = Vec::with_capacity(vertices.len());
    for (k, v) in vertices.iter().enumerate() {
        let mut xyz = [0.0; 3];
        for (c, name) in xyz.iter_mut().zip(["x", "y", "z"]) {
            *c = v
                .get(name)
                .and_then(scalar)
                .ok_or_else(|| error(format!("vertex {k} has no number '{name}'")))?;
        }
        positions.push(Point3::from(xyz));
    }
    let mut faces = Vec::new();
    if let Some(key) = face_list {
        for (k, f) in ply.payload.get("face").unwrap_or(&empty).iter().enumerate() {
            let face = f
                .get(key)
                .and_then(list)
                .ok_or_else(|| error(format!("face {k}: {key} is not a list of indices")))?;
            faces.push(face);
        }
    }
    Ok((positions, faces))
}

/// Bytes the elements read take in binary: each record's scalars, and each list's count and
/// items, in the types the header gives.
fn binary_bytes(header: &Header, payload: &Payload<DefaultElement>) -> usize {
    let mut bytes = 0;
    for (name, def) in &header.elements {
        for record in payload.get(name).into_iter().flatten() {
            for (key, property) in &def.properties {
                bytes += match &property.data_type {
                    PropertyType::Scalar(t) => scalar_size(t),
                    PropertyType::List(count, item) => {
                        let items = record.get(key).and_then(list).map_or(0, |l| l.len());
                        scalar_size(count) + items * scalar_size(item)
                    }
                };
            }
        }
    }
    bytes
}

/// Bytes of one binary scalar of type `t`.
fn scalar_size(t: &ScalarType) -> usize {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// The fewest bytes one `element` takes: its scalars' sizes and its lists' counts in binary,
/// a digit and a separator per property in ASCII.
fn least_bytes(element: &ElementDef, ascii: bool) -> u128 {
    let size = |t: &ScalarType| scalar_size(t) as u128;
    element
        .properties
        .values()
        .map(|p| match (&p.data_type, ascii) {
            (_, true) => 2,
            (PropertyType::Scalar(t), false) | (PropertyType::List(t, _), false) => size(t),
        })
        .sum()
}

fn scalar(p: &Property) -> Option<f64> {
    Some(match *p {
        Property::Char(v) => f64::from(v),
        Property::UChar(v) => f64::from(v),
        Property::Short(v) => f64::from(v),
        Property::UShort(v) => f64::from(v),
        Property::Int(v) => f64::from(v),
        Property::UInt(v) => f64::from(v),
        Property::Float(v) => f64::from(v),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// Indices of a list property; a negative index becomes one past any mesh's range, which
/// validation then names.
fn list(p: &Property) -> Option<Vec<usize>> {
    let signed = |v: i64| usize::try_from(v).unwrap_or(usize::MAX);
    Some(match p {
        Property::ListChar(v) => v.iter().map(|&i| signed(i64::from(i))).collect(),
        Property::ListUChar(v) => v.iter().map(|&i| usize::from(i)).collect(),
        Property::ListShort(v) => v.iter().map(|&i| signed(i64::from(i))).collect(),
        Property::ListUShort(v) => v.iter().map(|&i| usize::from(i)).collect(),
        Property::ListInt(v) => v.iter().map(|&i| signed(i64::from(i))).collect(),
        Property::ListUInt(v) => v.iter().map(|&i| i as usize).collect(),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: &str = "ply\nformat ascii 1.0\ncomment a square\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n4 0 1 2 3\n";

    #[test]
    fn ascii_and_binary_read_alike() {
        let (positions, faces) = parse(SQUARE.as_bytes(), Format::PlyAscii).unwrap();
        assert_eq!(positions[2], Point3::new(1.0, 1.0, 0.0));
        assert_eq!(faces, vec![vec![0, 1, 2, 3]]);
        // The same square, binary little endian, doubles and uint indices.
        let mut bytes = b"ply\nformat binary_little_endian 1.0\nelement vertex 4\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list uchar uint vertex_indices\nend_header\n".to_vec();
        for p in &positions {
            for c in p.iter() {
                bytes.extend(c.to_le_bytes());
            }
        }
        bytes.push(4);
        for i in 0u32..4 {
            bytes.extend(i.to_le_bytes());
        }
        assert_eq!(encoding(&bytes), Format::PlyBinary);
        assert_eq!(
            parse(&bytes, Format::PlyBinary).unwrap(),
            (positions, faces)
        );
        let cut = parse(&bytes[..bytes.len() - 3], Format::PlyBinary)
            .unwrap_err()
            .to_string();
        assert!(cut.starts_with("binary PLY"), "{cut}");
        // A header announcing far more than the file holds: corrupt, not a shell too large
        // (it said "4000001 vertices" for 4e9).
        let corrupt = parse(&bytes_with_count(&bytes, 4_000_000_000), Format::PlyBinary)
            .unwrap_err()
            .to_string();
        assert!(
            corrupt.contains("4000000000 vertices") && corrupt.contains("cut short or corrupt"),
            "{corrupt}"
        );
        // More data than the header announces: refused, ASCII and binary (the rest of the
        // shell was left out without a word).
        let mut longer = bytes.clone();
        longer.extend_from_slice(&bytes[bytes.len() - 17..]);
        let long = parse(&longer, Format::PlyBinary).unwrap_err().to_string();
        assert!(long.contains("17 bytes follow"), "{long}");
        let long = parse(format!("{SQUARE}4 0 1 2 3\n").as_bytes(), Format::PlyAscii)
            .unwrap_err()
            .to_string();
        assert!(long.contains("1 lines follow"), "{long}");
        // Trailing white space is no data.
        assert!(parse(format!("{SQUARE}\n\n").as_bytes(), Format::PlyAscii).is_ok());
    }

    /// `bytes` with its header's vertex count replaced by `count`.
    fn bytes_with_count(bytes: &[u8], count: u64) -> Vec<u8> {
        let at = bytes.windows(10).position(|w| w == b"end_header").unwrap();
        let header = String::from_utf8(bytes[..at].to_vec()).unwrap();
        let mut out = header
            .replacen(
                "element vertex 4\n",
                &format!("element vertex {count}\n"),
                1,
            )
            .into_bytes();
        out.extend_from_slice(&bytes[at..]);
        out
    }
}
