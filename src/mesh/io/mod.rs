//! Reading the mesh formats designers export: OBJ, STL (ASCII and binary), PLY (ASCII and
//! binary) and OFF, told apart by their content first (a PLY or OFF header, a binary STL's
//! size) and by the file's extension otherwise; then vertices at the same place are welded
//! (see [`super::weld`]), faces the wrong way round turned to agree with their neighbours
//! (see [`super::orient`]) and the mesh validated by [`PolyMesh::new`].
//!
//! Every front end that reads files goes through [`read`]: today that is the command line
//! only (the C ABI, C#, Python and Grasshopper take meshes as arrays from their host, and
//! [`prepare`] welds those where asked: `tp_mesh_new_welded`).

mod off;
mod ply;
mod stl;

use std::path::Path;

use nalgebra::Point3;
use serde::Serialize;

use super::weld::{self, DEFAULT_RELATIVE_TOLERANCE, WeldSummary};
use super::zip;
use super::{FileNumbering, MeshError, PolyMesh, obj, orient};

/// Positions and faces as a file gives them, before welding and validation.
pub type Raw = (Vec<Point3<f64>>, Vec<Vec<usize>>);

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Format {
    /// Wavefront OBJ.
    Obj,
    /// STL, ASCII flavour (`solid ... facet normal ...`).
    StlAscii,
    /// STL, binary flavour (80-byte header, triangle count, 50 bytes per triangle).
    StlBinary,
    /// PLY, ASCII encoding.
    PlyAscii,
    /// PLY, binary encoding (either byte order).
    PlyBinary,
    /// Object File Format (`OFF`, `COFF`, `NOFF`, ...).
    Off,
}

impl Format {
    /// The name error messages use.
    pub fn name(self) -> &'static str {
        match self {
            Format::Obj => "OBJ",
            Format::StlAscii => "ASCII STL",
            Format::StlBinary => "binary STL",
            Format::PlyAscii => "ASCII PLY",
            Format::PlyBinary => "binary PLY",
            Format::Off => "OFF",
        }
    }
}

/// Whether and how far to weld coincident vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Weld {
    /// Keep every vertex of the file (STL still joins identical corners: it has no shared
    /// vertices at all).
    Off,
    /// Join vertices closer than this fraction of the bounding-box diagonal.
    Relative(f64),
}

impl Default for Weld {
    fn default() -> Self {
        Weld::Relative(DEFAULT_RELATIVE_TOLERANCE)
    }
}

/// A mesh read from a file, with what reading it did.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The validated mesh.
    pub mesh: PolyMesh,
    /// The format it was read as.
    pub format: Format,
    /// What welding did.
    pub weld: WeldSummary,
    /// Faces turned over to agree with their neighbours (each piece keeps the side most of
    /// its faces face; see [`orient::orient`]).
    pub turned_faces: usize,
    /// The file's numbers of the mesh's faces and vertices (welding removes faces and joins
    /// vertices, zipping splits triangles): face numbers users give or read are the file's.
    pub numbering: FileNumbering,
}

/// Reads, welds and validates a mesh file of any supported format.
///
/// # Errors
/// [`MeshError::Io`] if the file cannot be read or is larger than [`obj::MAX_FILE_BYTES`];
/// otherwise as [`parse`].
pub fn read(path: &Path, weld: Weld) -> Result<Loaded, MeshError> {
    let size = std::fs::metadata(path)
        .map_err(|e| obj::io_error(path, &e))?
        .len();
    if size > obj::MAX_FILE_BYTES {
        return Err(MeshError::Io {
            path: path.display().to_string(),
            message: format!(
                "the file has {size} bytes; a mesh file may have at most {} (split the shell into parts)",
                obj::MAX_FILE_BYTES
            ),
        });
    }
    let bytes = std::fs::read(path).map_err(|e| obj::io_error(path, &e))?;
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    parse(&bytes, extension.as_deref(), weld)
}

/// Reads a mesh from the bytes of a file whose extension (without the dot, lower case) is
/// `extension`, welds and validates it.
///
/// # Errors
/// [`MeshError::Format`] naming the format when the bytes cannot be read as it (or as any
/// format), [`MeshError::TooLarge`], [`MeshError::NonOrientable`] for a one-sided surface,
/// then any validation error of [`PolyMesh::new`].
pub fn parse(bytes: &[u8], extension: Option<&str>, weld: Weld) -> Result<Loaded, MeshError> {
    // A UTF-8 byte-order mark (Windows editors write one) is no part of a text file's first
    // line: left in, an OBJ lost its first vertex and every face pointed one vertex off.
    let bytes = match bytes.strip_prefix(b"\xEF\xBB\xBF") {
        Some(rest) if !stl::is_binary(bytes) => rest,
        _ => bytes,
    };
    let format = detect(bytes, extension)?;
    let (positions, faces) = match format {
        Format::Obj => obj::parse_raw(&text(bytes, format)?)?,
        Format::Off => off::parse(&text(bytes, format)?)?,
        Format::StlAscii | Format::StlBinary => stl::parse(bytes, format)?,
        Format::PlyAscii | Format::PlyBinary => ply::parse(bytes, format)?,
    };
    single_precision_far_out(&positions, &faces, format)?;
    let as_read = FileNumbering::identity(faces.len(), positions.len());
    let (positions, faces, numbering) = if matches!(format, Format::StlAscii | Format::StlBinary) {
        // STL has no shared vertices: identical corners are one vertex, always and silently.
        let (positions, faces, _, joined) = weld::weld_traced(positions, faces, 0.0);
        (positions, faces, joined)
    } else {
        (positions, faces, as_read)
    };
    let prepared = prepare(positions, faces, weld, numbering)?;
    Ok(Loaded {
        mesh: prepared.mesh,
        format,
        weld: prepared.weld,
        turned_faces: prepared.turned_faces,
        numbering: prepared.numbering,
    })
}

/// A mesh made from positions and faces as a file or a caller gives them: welded, zipped,
/// turned to agree and validated ([`prepare`]).
#[derive(Debug, Clone)]
pub struct Prepared {
    /// The validated mesh.
    pub mesh: PolyMesh,
    /// What welding and zipping did.
    pub weld: WeldSummary,
    /// Faces turned over to agree with their neighbours.
    pub turned_faces: usize,
    /// The given numbers of the mesh's faces and vertices.
    pub numbering: FileNumbering,
}

/// What every front end does to a mesh it is given before the stages take it: vertices
/// closer than `weld`'s share of the diagonal of the used vertices joined and the faces
/// this collapses or repeats removed ([`weld::weld_traced`]), the cracks of a triangle mesh
/// zipped ([`zip::zip_traced`]), faces turned to agree with their neighbours
/// ([`orient::orient`]), and the result validated by [`PolyMesh::new`]. `numbering` gives
/// the given numbers of `faces` and `positions` (identity for a caller's arrays), and the
/// result's is composed with it.
///
/// # Errors
/// [`MeshError::NonOrientable`] for a one-sided surface, then any validation error of
/// [`PolyMesh::new`], faces and vertices named in the given numbers.
pub fn prepare(
    positions: Vec<Point3<f64>>,
    faces: Vec<Vec<usize>>,
    weld: Weld,
    numbering: FileNumbering,
) -> Result<Prepared, MeshError> {
    let (positions, faces, summary, numbering) = match weld {
        Weld::Relative(fraction) if fraction.is_finite() && fraction > 0.0 => {
            let tolerance = fraction * diagonal(&positions, &faces);
            let (positions, faces, mut summary, welded) =
                weld::weld_traced(positions, faces, tolerance);
            let numbering = numbering.then(&welded);
            // Cracks between patches meshed apart, once coincident vertices are one; in
            // triangle meshes only (STL, soups, triangulated exports): a quad mesh is a
            // remesher's or the user's own, given to be tiled as it is.
            let (faces, zipped, numbering) = if faces.iter().all(|f| f.len() == 3) {
                let (faces, zipped, split) = zip::zip_traced(&positions, faces);
                (faces, zipped, numbering.then(&split))
            } else {
                (faces, 0, numbering)
            };
            summary.zipped_vertices = zipped;
            (positions, faces, summary, numbering)
        }
        _ => (positions, faces, WeldSummary::OFF, numbering),
    };
    let mut faces = faces;
    // Faces and vertices an error names are counted as given.
    let in_file = |e: MeshError| e.in_file_numbers(&numbering);
    let turned_faces = orient::orient(&mut faces).map_err(in_file)?;
    let mesh = PolyMesh::new(positions, faces).map_err(in_file)?;
    Ok(Prepared {
        mesh,
        weld: summary,
        turned_faces,
        numbering,
    })
}

/// Refuses coordinates that went through single precision (every one a 32-bit float: binary
/// STL, STL and PLY read as floats, some exporters' OBJ) so far from the origin that their
/// steps exceed a thousandth of the model: a shell 6 m across at a site's coordinates (y =
/// 5,200,000) is quantized to 0.5 m, and its faces then meet as fins or vanish, which the
/// checks downstream named as if the mesh were drawn so.
fn single_precision_far_out(
    positions: &[Point3<f64>],
    faces: &[Vec<usize>],
    format: Format,
) -> Result<(), MeshError> {
    let coordinates = || positions.iter().flat_map(|p| p.iter().copied());
    if !coordinates().all(|c| !c.is_finite() || f64::from(c as f32) == c) {
        return Ok(());
    }
    let far = coordinates()
        .filter(|c| c.is_finite())
        .fold(0.0, |m: f64, c| m.max(c.abs()));
    let size = diagonal(positions, faces);
    // The spacing of 32-bit floats at `far`: 2^(exponent - 23).
    let step = if far > 0.0 {
        2f64.powi(far.log2().floor() as i32 - 23)
    } else {
        0.0
    };
    if size > 0.0 && step > 1e-3 * size {
        return Err(MeshError::Format {
            format: format.name(),
            message: format!(
                "the coordinates are 32-bit floats, which {far:.0} from the origin are {step} apart, more than a thousandth of the model ({size:.3} across): its shape is lost; move the model near the origin before exporting (Rhino: Move; or export relative to a local origin), or export OBJ with full precision"
            ),
        });
    }
    Ok(())
}

/// Bounding-box diagonal of the finite positions that faces use (0 for none).
fn diagonal(positions: &[Point3<f64>], faces: &[Vec<usize>]) -> f64 {
    // Only the vertices a face uses: a stray vertex 250 km off (or at the origin of a
    // georeferenced model) made the weld tolerance swallow the whole mesh.
    let mut used = vec![false; positions.len()];
    for &v in faces.iter().flatten() {
        if let Some(u) = used.get_mut(v) {
            *u = true;
        }
    }
    let mut finite = positions
        .iter()
        .zip(&used)
        .filter(|&(p, &u)| u && super::usable_point(p))
        .map(|(p, _)| p);
    let Some(first) = finite.next() else {
        return 0.0;
    };
    let (lo, hi) = finite.fold((*first, *first), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    (hi - lo).norm()
}

/// The format of `bytes`: a PLY or OFF header or a binary STL's exact size decide first, then
/// the extension, then an ASCII STL's `solid` or OBJ's `v` lines.
fn detect(bytes: &[u8], extension: Option<&str>) -> Result<Format, MeshError> {
    if bytes.starts_with(b"ply\n") || bytes.starts_with(b"ply\r\n") {
        return Ok(ply::encoding(bytes));
    }
    if stl::is_binary(bytes) {
        return Ok(Format::StlBinary);
    }
    let head = first_word(bytes);
    let solid = head.eq_ignore_ascii_case("solid");
    if off::is_header(&head) {
        return Ok(Format::Off);
    }
    let binary = looks_binary(bytes);
    match extension {
        Some("obj") => return Ok(Format::Obj),
        Some("off") => return Ok(Format::Off),
        Some("ply") => return Ok(Format::PlyAscii),
        Some("stl") if binary || solid || !looks_obj(bytes) => {
            return Ok(if binary || !solid {
                Format::StlBinary
            } else {
                Format::StlAscii
            });
        }
        _ => {}
    }
    if !binary {
        if solid {
            return Ok(Format::StlAscii);
        }
        if looks_obj(bytes) {
            return Ok(Format::Obj);
        }
    }
    Err(MeshError::Format {
        format: "mesh file",
        message: format!(
            "not a mesh format this program reads{}; give OBJ, STL (ASCII or binary), PLY or OFF, named .obj, .stl, .ply or .off",
            extension.map_or(String::new(), |e| format!(" (extension .{e})"))
        ),
    })
}

/// True when some line of `bytes` starts with an OBJ vertex or face (`v`, `f`): OBJ text,
/// whatever the file is named.
fn looks_obj(bytes: &[u8]) -> bool {
    String::from_utf8_lossy(bytes)
        .lines()
        .any(|l| matches!(l.split_whitespace().next(), Some("v" | "f")))
}

/// The first whitespace-separated word of the text at the start of `bytes`.
fn first_word(bytes: &[u8]) -> String {
    let head = &bytes[..bytes.len().min(256)];
    String::from_utf8_lossy(head)
        .split_whitespace()
        .next()
        .unwrap_or("")
        .to_owned()
}

/// True when the start of `bytes` holds a NUL byte: no text format has one.
fn looks_binary(bytes: &[u8]) -> bool {
    bytes[..bytes.len().min(4096)].contains(&0)
}

/// The bytes as text for a text format; bytes that are not UTF-8 (in comments or group names
/// of older exporters) become replacement characters, but a binary file is refused.
fn text(bytes: &[u8], format: Format) -> Result<std::borrow::Cow<'_, str>, MeshError> {
    if looks_binary(bytes) {
        return Err(MeshError::Format {
            format: format.name(),
            message:
                "the file is binary, not text: is it a binary STL or PLY with the wrong extension?"
                    .into(),
        });
    }
    let text = String::from_utf8_lossy(bytes);
    // Lines ended by a carriage return alone (classic Mac OS) read as one line otherwise.
    if text.contains('\r') && !text.contains('\n') {
        return Ok(std::borrow::Cow::Owned(text.replace('\r', "\n")));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn content_decides_before_the_extension() {
        let off = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(detect(off, Some("obj")).unwrap(), Format::Off);
        let ply = b"ply\nformat ascii 1.0\nend_header\n";
        assert_eq!(detect(ply, None).unwrap(), Format::PlyAscii);
        let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        assert_eq!(detect(obj, Some("txt")).unwrap(), Format::Obj);
        assert_eq!(detect(obj, None).unwrap(), Format::Obj);
        let error = detect(b"hello\n", Some("dwg")).unwrap_err().to_string();
        assert!(
            error.contains(".dwg") && error.contains("OBJ, STL"),
            "{error}"
        );
    }

    /// Two triangles of a unit square, as an OBJ and as an OFF file.
    const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
    const OFF: &str = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

    #[test]
    fn a_byte_order_mark_and_lone_carriage_returns_read_as_plain_text() {
        let plain = parse(OBJ.as_bytes(), Some("obj"), Weld::default()).unwrap();
        // Before: the mark joined the first line, which lost its vertex, and every face
        // pointed one vertex off (or past the last).
        for (variant, extension) in [
            (format!("\u{feff}{OBJ}"), "obj"),
            (OBJ.replace('\n', "\r"), "obj"),
            (format!("\u{feff}{}", OBJ.replace('\n', "\r\n")), "obj"),
            (format!("\u{feff}{OFF}"), "off"),
        ] {
            let read = parse(variant.as_bytes(), Some(extension), Weld::default())
                .unwrap_or_else(|e| panic!("{variant:?}: {e}"));
            assert_eq!(read.mesh.positions(), plain.mesh.positions(), "{variant:?}");
            assert_eq!(read.mesh.faces(), plain.mesh.faces(), "{variant:?}");
        }
    }

    #[test]
    fn single_precision_far_from_the_origin_is_refused_and_near_it_read() {
        // A strip of 20 triangles 6 m long, at a site's coordinates and at the origin.
        let strip = |y: f32| -> Vec<[[f32; 3]; 3]> {
            (0..10)
                .flat_map(|i| {
                    let x = 0.6 * i as f32;
                    [
                        [[x, y, 0.0], [x + 0.6, y, 0.0], [x + 0.6, y + 0.6, 0.1]],
                        [[x, y, 0.0], [x + 0.6, y + 0.6, 0.1], [x, y + 0.6, 0.1]],
                    ]
                })
                .collect()
        };
        let far = stl::tests::binary(&strip(5_200_000.0));
        let error = parse(&far, Some("stl"), Weld::default())
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("32-bit floats")
                && error.contains("0.5 apart")
                && error.contains("near the origin"),
            "{error}"
        );
        let near = stl::tests::binary(&strip(0.0));
        assert_eq!(
            parse(&near, Some("stl"), Weld::default())
                .unwrap()
                .mesh
                .face_count(),
            20
        );
    }

    #[test]
    fn a_vertex_no_face_uses_does_not_set_the_weld_tolerance() {
        // A 1 m square of 0.1 m triangles and, unused, a vertex 250 km away: the tolerance of
        // 1e-6 of the diagonal was 0.25 m and welded the square away.
        let mut text = String::new();
        for j in 0..=10 {
            for i in 0..=10 {
                text += &format!("v {} {} 0\n", i as f64 * 0.1, j as f64 * 0.1);
            }
        }
        for j in 0..10 {
            for i in 0..10 {
                let v = 1 + i + 11 * j;
                text += &format!(
                    "f {} {} {}\nf {} {} {}\n",
                    v,
                    v + 1,
                    v + 12,
                    v,
                    v + 12,
                    v + 11
                );
            }
        }
        text += "v 250000 0 0\n";
        let read = parse(text.as_bytes(), Some("obj"), Weld::default()).unwrap();
        assert_eq!(read.mesh.face_count(), 200);
        assert_eq!(read.weld.merged_vertices, 0);
    }
}
