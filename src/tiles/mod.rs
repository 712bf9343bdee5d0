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
//!
//! Beyond the paper, [`finish`] makes the tiles buildable: it cuts tiles that cross the
//! input surface's boundary ([`clip`]), groups the cut shapes into a cut list ([`cutlist`])
//! and numbers the tiles in laying order ([`sequence`]).

pub mod clip;
pub mod cutlist;
mod frame;
pub mod sequence;

pub use clip::{Cut, SurfaceBoundary};
pub use cutlist::CutGroup;
pub use frame::Frame;
pub use sequence::{Sequence, SequenceOptions};

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
    /// A full or half tile cut to the surface's boundary (its [`Tile::cut`] says how).
    Boundary,
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
    /// For a boundary tile, the part kept after cutting; `None` for an uncut tile.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cut: Option<Cut>,
    /// Its cut-list label (`F`, `H`, `B1`, ...); empty until [`finish`] runs.
    pub label: String,
    /// Its place in the laying order, from 0; set by [`finish`].
    pub step: usize,
}

/// How tiles are made buildable: cutting, grouping and ordering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FinishOptions {
    /// Cutting tolerance in model units: tiles the boundary enters by no more than this stay
    /// whole, and cut shapes this close count as the same shape.
    pub tolerance: f64,
    /// Pieces narrower than this ([`Cut::kept_width`]) are slivers: reported, not emitted.
    pub min_kept_width: f64,
    /// Where the vault stands, for the laying order.
    pub sequence: SequenceOptions,
}

impl FinishOptions {
    /// Defaults for a tile: tolerance 1 % of its width, slivers below a fifth of its width,
    /// `+z` up, supports within one tile width of the lowest boundary point.
    pub fn for_spec(spec: &TileSpec) -> Self {
        Self {
            tolerance: spec.width / 100.0,
            min_kept_width: spec.width / 5.0,
            sequence: SequenceOptions { up: Vector3::z(), support_band: spec.width },
        }
    }

    /// Checks that the tolerances are finite and not negative and `up` is a direction.
    ///
    /// # Errors
    /// [`TileError::InvalidSpec`] naming the first bad value.
    pub fn validate(&self) -> Result<(), TileError> {
        let values = [("tolerance", self.tolerance), ("min_kept_width", self.min_kept_width), ("support_band", self.sequence.support_band)];
        for (name, value) in values {
            if !(value.is_finite() && value >= 0.0) {
                return Err(TileError::InvalidSpec { name, value });
            }
        }
        let up = self.sequence.up;
        if !(up.iter().all(|c| c.is_finite()) && up.norm() > 0.0) {
            return Err(TileError::InvalidSpec { name: "up", value: up.norm() });
        }
        Ok(())
    }
}

/// Why a tile was left out.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DropReason {
    /// No part of it lies on the surface.
    Outside,
    /// What lies on the surface is narrower than the minimum kept width.
    Sliver,
}

/// A tile that [`finish`] did not emit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DroppedTile {
    /// Faces it would have covered.
    pub faces: Vec<usize>,
    /// Why it was dropped.
    pub reason: DropReason,
    /// Area that lay on the surface.
    pub kept_area: f64,
    /// Width of that area ([`Cut::kept_width`]).
    pub kept_width: f64,
}

/// What [`finish`] found besides the tiles.
#[derive(Debug, Clone, PartialEq)]
pub struct Finished {
    /// Tiles left out: off the surface, or slivers.
    pub dropped: Vec<DroppedTile>,
    /// Cut shapes with counts.
    pub cut_list: Vec<CutGroup>,
    /// Summary of the laying order.
    pub sequence: Sequence,
}

/// Makes tiles buildable: cuts them to the boundary of `surface` (the input surface; the quad
/// mesh itself when `None`), drops tiles off the surface and slivers, groups the cut shapes
/// into a cut list and labels each tile, and numbers the tiles in laying order.
pub fn finish(quads: &PolyMesh, surface: Option<&PolyMesh>, tiles: Vec<Tile>, options: &FinishOptions) -> (Vec<Tile>, Finished) {
    let reference = surface.unwrap_or(quads);
    let cell = tiles.first().map_or(1.0, |t| t.size[0].max(t.size[1]));
    let boundary = SurfaceBoundary::new(reference, cell);
    let mut kept = Vec::with_capacity(tiles.len());
    let mut dropped = Vec::new();
    for mut tile in tiles {
        let drop = |tile: &Tile, reason, kept_area, kept_width| DroppedTile { faces: tile.faces.clone(), reason, kept_area, kept_width };
        match boundary.clip(&tile, options.tolerance) {
            clip::Clipped::Whole => kept.push(tile),
            clip::Clipped::Outside => dropped.push(drop(&tile, DropReason::Outside, 0.0, 0.0)),
            clip::Clipped::Cut(cut) => {
                if cut.kept_width() < options.min_kept_width {
                    dropped.push(drop(&tile, DropReason::Sliver, cut.area(), cut.kept_width()));
                } else {
                    tile.kind = TileKind::Boundary;
                    tile.cut = Some(cut);
                    kept.push(tile);
                }
            }
        }
    }
    let cut_list = cutlist::cut_list(&mut kept, options.tolerance);
    let sequence = sequence::laying_order(quads, &mut kept, &options.sequence);
    (kept, Finished { dropped, cut_list, sequence })
}

/// Why tiles could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TileError {
    /// A tile dimension or finishing option is out of range.
    #[error("tile {name} {value} must be a finite number > 0 (joint, tolerances >= 0; up a non-zero direction)")]
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
        Self { kind, faces, frame, size, corners, cut: None, label: String::new(), step: 0 }
    }

    /// Area of the tile's face that is kept: all of it unless it was cut.
    pub fn kept_area(&self) -> f64 {
        self.cut.as_ref().map_or(self.size[0] * self.size[1], Cut::area)
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
            TileKind::Boundary => "boundary",
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
