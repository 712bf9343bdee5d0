//! Stage 3 (paper section 3.5): a box for every matched pair, a half tile for every unmatched
//! quad.
//!
//! Frame of a full tile, as in the paper: the origin is the midpoint of the two face
//! centroids; the length axis `x` points from the first centroid to the second; the thickness
//! axis `z` is the normal of the least-squares plane through the vertices of both faces; the
//! height axis is `y = z × x`. `x` is projected into the plane so the frame is orthonormal.
//!
//! Side of the thickness: the box's bottom face lies in the frame's `xy` plane and the box
//! extends along `+z`, the side the faces' normals point to (counter-clockwise vertex order
//! seen from there). For a shell modelled with normals pointing up and out, tiles sit on top
//! of the surface, as when laid on formwork; flip the mesh to lay them underneath.

mod frame;

pub use frame::Frame;

use nalgebra::{Point3, Vector3};
use serde::Serialize;
use thiserror::Error;

use crate::mesh::{PolyMesh, Topology};
use crate::pattern::Pattern;

/// Nominal tile dimensions in model units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TileSpec {
    /// Length of a full tile (along the pair).
    pub length: f64,
    /// Width of a tile (across the pair).
    pub width: f64,
    /// Thickness.
    pub thickness: f64,
    /// Mortar joint between tiles.
    pub joint: f64,
}

impl TileSpec {
    /// Target quad edge for this tile: half a tile plus half a joint, `(L + joint) / 2`.
    pub fn target_edge(&self) -> f64 {
        (self.length + self.joint) / 2.0
    }

    /// Checks that every dimension is a finite positive number (the joint may be zero).
    ///
    /// # Errors
    /// [`TileError::InvalidSpec`] naming the first bad dimension.
    pub fn validate(&self) -> Result<(), TileError> {
        let dims = [("length", self.length), ("width", self.width), ("thickness", self.thickness)];
        for (name, value) in dims {
            if !(value.is_finite() && value > 0.0) {
                return Err(TileError::InvalidSpec { name, value });
            }
        }
        if !(self.joint.is_finite() && self.joint >= 0.0) {
            return Err(TileError::InvalidSpec { name: "joint", value: self.joint });
        }
        Ok(())
    }
}

/// Whether a tile is whole or cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TileKind {
    /// A standard tile over two faces.
    Full,
    /// Half a tile over one unmatched quad: needs a cut.
    Half,
}

/// One placed tile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Tile {
    /// Full or half.
    pub kind: TileKind,
    /// Faces it covers (two for a full tile, one for a half tile).
    pub faces: Vec<usize>,
    /// Its local frame: origin, length, height and thickness axes.
    pub frame: Frame,
    /// Box size along the frame axes: length, width, thickness.
    pub size: [f64; 3],
    /// Box corners: bottom face (`z = 0`) counter-clockwise from `(-x, -y)`, then the top face
    /// (`z = thickness`) in the same order.
    pub corners: [[f64; 3]; 8],
}

/// Why tiles could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TileError {
    /// A tile dimension is zero, negative or not finite.
    #[error("tile {name} {value} must be a finite number > 0 (joint >= 0)")]
    InvalidSpec {
        /// Which dimension.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// The tile is longer than the whole mesh.
    #[error("tile length {length} is larger than the whole mesh (bounding-box diagonal {diagonal}); are the tile and the mesh in the same units?")]
    TileLargerThanMesh {
        /// Tile length.
        length: f64,
        /// Mesh bounding-box diagonal.
        diagonal: f64,
    },
    /// A pair or face refers to a face that does not exist.
    #[error("face {face} does not exist (the mesh has {face_count} faces)")]
    FaceOutOfRange {
        /// The index given.
        face: usize,
        /// Number of faces.
        face_count: usize,
    },
    /// A pair names faces that do not share an edge.
    #[error("pair [{a}, {b}]: the faces do not share an edge")]
    NotAdjacent {
        /// First face.
        a: usize,
        /// Second face.
        b: usize,
    },
    /// A face is in two pairs, or paired and unpaired.
    #[error("face {face} is used by more than one tile")]
    FaceUsedTwice {
        /// The face at fault.
        face: usize,
    },
    /// A pair or half tile uses a face that is not a quad.
    #[error("face {face} has {corners} corners; tiles are built on quads only")]
    NotQuad {
        /// The face at fault.
        face: usize,
        /// Its number of corners.
        corners: usize,
    },
}

/// Builds the tiles of `pattern` on `mesh`: one full tile per pair (in pair order), then one
/// half tile per unpaired quad (in face order).
///
/// # Errors
/// An invalid spec, or a pattern that does not fit the mesh (pairs read from a file may
/// come from another mesh).
pub fn build(mesh: &PolyMesh, pattern: &Pattern, spec: &TileSpec) -> Result<Vec<Tile>, TileError> {
    spec.validate()?;
    let (min, max) = mesh.bounding_box();
    let diagonal = (max - min).norm();
    if spec.length > diagonal {
        return Err(TileError::TileLargerThanMesh { length: spec.length, diagonal });
    }
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut used = vec![false; mesh.face_count()];
    let mut claim = |f: usize| -> Result<(), TileError> {
        let slot = used.get_mut(f).ok_or(TileError::FaceOutOfRange { face: f, face_count: mesh.face_count() })?;
        if std::mem::replace(slot, true) {
            return Err(TileError::FaceUsedTwice { face: f });
        }
        if !mesh.is_quad(f) {
            return Err(TileError::NotQuad { face: f, corners: mesh.faces()[f].len() });
        }
        Ok(())
    };

    let mut tiles = Vec::with_capacity(pattern.pairs.len() + pattern.unpaired.len());
    for &[a, b] in &pattern.pairs {
        claim(a)?;
        claim(b)?;
        let adjacent = topology.face_edges(a).iter().any(|&e| topology.edges()[e].other_face(a) == Some(b));
        if !adjacent {
            return Err(TileError::NotAdjacent { a, b });
        }
        let frame = Frame::for_pair(mesh, a, b);
        tiles.push(Tile::new(TileKind::Full, vec![a, b], frame, [spec.length, spec.width, spec.thickness]));
    }
    for &f in &pattern.unpaired {
        claim(f)?;
        let frame = Frame::for_face(mesh, f);
        tiles.push(Tile::new(TileKind::Half, vec![f], frame, [spec.length / 2.0, spec.width, spec.thickness]));
    }
    Ok(tiles)
}

impl Tile {
    fn new(kind: TileKind, faces: Vec<usize>, frame: Frame, size: [f64; 3]) -> Self {
        let [l, w, t] = size;
        let corner = |sx: f64, sy: f64, z: f64| -> [f64; 3] {
            let p: Point3<f64> = frame.origin + frame.x * (sx * l / 2.0) + frame.y * (sy * w / 2.0) + frame.z * z;
            [p.x, p.y, p.z]
        };
        let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let mut corners = [[0.0; 3]; 8];
        for (k, (sx, sy)) in square.iter().enumerate() {
            corners[k] = corner(*sx, *sy, 0.0);
            corners[k + 4] = corner(*sx, *sy, t);
        }
        Self { kind, faces, frame, size, corners }
    }

    /// Position of a point given in the tile's frame.
    pub fn to_world(&self, local: Vector3<f64>) -> Point3<f64> {
        self.frame.origin + self.frame.x * local.x + self.frame.y * local.y + self.frame.z * local.z
    }
}

/// Formats tiles as OBJ: one object per tile named `full_<i>` or `half_<i>` (`i` = tile
/// index), six outward-facing quads per box.
pub fn to_obj(tiles: &[Tile]) -> String {
    use std::fmt::Write as _;
    const BOX_FACES: [[usize; 4]; 6] = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]];
    let mut out = String::new();
    for (i, tile) in tiles.iter().enumerate() {
        let kind = match tile.kind {
            TileKind::Full => "full",
            TileKind::Half => "half",
        };
        let _ = writeln!(out, "o {kind}_{i}");
        for c in &tile.corners {
            let _ = writeln!(out, "v {} {} {}", c[0], c[1], c[2]);
        }
        for face in BOX_FACES {
            let [a, b, c, d] = face.map(|k| 8 * i + k + 1);
            let _ = writeln!(out, "f {a} {b} {c} {d}");
        }
    }
    out
}
