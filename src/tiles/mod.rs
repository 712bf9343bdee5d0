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
mod excluded;
mod fill;
pub mod fit;
mod frame;
pub mod outline;
pub mod sequence;
pub mod solid;
mod tears;

pub use clip::{Cut, SurfaceBoundary};
pub use cutlist::CutGroup;
pub use excluded::{ExcludedArea, without_faces};
pub use fit::{FitOptions, FitStatus, FitSummary};
pub use frame::Frame;
pub use sequence::{SLOPE_DEGREES, Sequence, SequenceOptions, Support};

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

    /// Distance between neighbouring courses: a tile's width plus a joint, `W + joint`.
    pub fn course_pitch(&self) -> f64 {
        self.width + self.joint
    }

    /// The quad edge to remesh with. Tiles laid either way across square quads sit best on
    /// quads of [`TileSpec::target_edge`] (the paper's choice). In courses, the quads'
    /// height across the courses is what no placement can change, so they are made as high
    /// as a course ([`TileSpec::course_pitch`]) where that is larger, and the fit stage
    /// closes the head joints along each course (see [`fit`]).
    pub fn quad_edge(&self, in_courses: bool) -> f64 {
        if in_courses {
            self.target_edge().max(self.course_pitch())
        } else {
            self.target_edge()
        }
    }

    /// Checks that every dimension is a finite positive number (the joint may be zero), the
    /// joint narrower than the tile and the tile thinner than it is long.
    ///
    /// # Errors
    /// [`TileError::InvalidSpec`] naming the first bad dimension, or
    /// [`TileError::OutOfProportion`].
    pub fn validate(&self) -> Result<(), TileError> {
        let dims = [
            ("length", self.length),
            ("width", self.width),
            ("thickness", self.thickness),
        ];
        for (name, value) in dims {
            if !(value.is_finite() && value > 0.0) {
                return Err(TileError::InvalidSpec { name, value });
            }
        }
        if !(self.joint.is_finite() && self.joint >= 0.0) {
            return Err(TileError::InvalidSpec {
                name: "joint",
                value: self.joint,
            });
        }
        for (name, value, than, limit) in [
            ("joint", self.joint, "width", self.width),
            ("thickness", self.thickness, "length", self.length),
        ] {
            if value >= limit {
                return Err(TileError::OutOfProportion {
                    name,
                    value,
                    than,
                    limit,
                });
            }
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
    /// A full or half tile cut by the fit stage where it could not be made to fit its
    /// neighbours (its [`Tile::cut`] says how); a boundary tile also cut by the fit stays
    /// [`TileKind::Boundary`] with [`Tile::fit_cut`] set.
    FitCut,
}

/// One placed tile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Tile {
    /// Full or half.
    pub kind: TileKind,
    /// Faces it covers (two for a full tile, one for a half tile, none for a filler piece
    /// beyond the quad mesh's boundary).
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
    /// Whether the fit stage cut it (see [`fit::resolve_overlaps`]).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub fit_cut: bool,
}

/// How tiles are made buildable: cutting, grouping and ordering.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct FinishOptions {
    /// Cutting tolerance in model units: tiles the boundary enters by no more than this stay
    /// whole, and cut shapes this close count as the same shape.
    pub tolerance: f64,
    /// Pieces narrower than this ([`Cut::kept_width`]) are slivers: reported, not emitted.
    pub min_kept_width: f64,
    /// Where the vault stands, for the laying order.
    pub sequence: SequenceOptions,
    /// The fit of joints (stage 3b) between placing and cutting; `None` keeps the section
    /// 3.5 placement.
    pub fit: Option<FitOptions>,
    /// Model units per millimetre, for figures stated in millimetres (the report's share of
    /// joints within 2 and 5 mm); 0.001 for a model in metres.
    pub units_per_mm: f64,
    /// Cut the tiles to the creases that part the surface into sheets, half a joint short on
    /// each side, place them on their own sheet and keep filler pieces to it
    /// (`mesh::crease`; default on). Off, the surface is one sheet, as
    /// [`crate::remesh::RemeshOptions::creases`] off leaves it.
    pub creases: bool,
}

impl FinishOptions {
    /// Defaults for a tile: tolerance 1 % of its width, slivers below a fifth of its width,
    /// `+z` up, supports within one tile width of the lowest boundary point, the fit stage
    /// with [`FitOptions::for_spec`], a model in metres.
    pub fn for_spec(spec: &TileSpec) -> Self {
        Self {
            tolerance: spec.width / 100.0,
            min_kept_width: spec.width / 5.0,
            sequence: SequenceOptions {
                up: Vector3::z(),
                support_band: spec.width,
            },
            fit: Some(FitOptions::for_spec(spec)),
            units_per_mm: 0.001,
            creases: true,
        }
    }

    /// Checks that the tolerances are finite and not negative and `up` is a direction.
    ///
    /// # Errors
    /// [`TileError::InvalidSpec`] naming the first bad value, [`TileError::NoUpDirection`]
    /// for an `up` that is zero or not finite.
    pub fn validate(&self) -> Result<(), TileError> {
        let values = [
            ("tolerance", self.tolerance),
            ("min_kept_width", self.min_kept_width),
            ("support_band", self.sequence.support_band),
        ];
        for (name, value) in values {
            if !(value.is_finite() && value >= 0.0) {
                return Err(TileError::InvalidSpec { name, value });
            }
        }
        if !(self.units_per_mm.is_finite() && self.units_per_mm > 0.0) {
            return Err(TileError::InvalidSpec {
                name: "units_per_mm",
                value: self.units_per_mm,
            });
        }
        if let Some(fit) = &self.fit {
            fit.validate()?;
        }
        let up = self.sequence.up;
        if !(up.iter().all(|c| c.is_finite()) && up.norm() > 0.0) {
            return Err(TileError::NoUpDirection {
                up: [up.x, up.y, up.z],
            });
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
    /// Filler pieces placed beyond the quad mesh's boundary and in the fit's tears (tiles
    /// with no faces).
    pub fillers: usize,
    /// Of `fillers`, the pieces filling holes the fit left (`tears.rs`), and the whole pieces
    /// the fit itself laid in the rooms of its courses ([`FitSummary::room_pieces`]).
    pub tear_pieces: usize,
    /// Of `tear_pieces`, those cut to the room their neighbours leave away from the
    /// surface's edge: the cuts the fit's tears alone ask for.
    pub tear_cuts: usize,
    /// Of `tear_pieces`, whole half tiles laid where the room held one with joints within
    /// half a joint of the nominal one, by the tear fill or in the fit's rooms (no cut on
    /// site: halves are cut off site, as the pattern's are).
    pub tear_halves: usize,
    /// Whether the fill of those holes was stopped (by [`finish_with`]'s `keep_going`)
    /// before every hole was tried.
    pub tear_fill_stopped: bool,
    /// Cut shapes with counts.
    pub cut_list: Vec<CutGroup>,
    /// Summary of the laying order.
    pub sequence: Sequence,
    /// Per kept tile, how far its bottom face stands off the surface ([`lifts`]).
    pub lifts: Vec<f64>,
}

/// Makes tiles buildable: where the quad mesh falls short of the boundary of `surface` (the
/// input surface; the quad mesh itself when `None`), adds filler pieces continuing the
/// courses; cuts every tile to that boundary, drops tiles off the surface and slivers; groups
/// the cut shapes into a cut list and labels each tile; numbers the tiles in laying order.
pub fn finish(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    tiles: Vec<Tile>,
    spec: &TileSpec,
    options: &FinishOptions,
) -> (Vec<Tile>, Finished) {
    finish_with(quads, surface, tiles, spec, options, None, &mut || true)
}

/// [`finish`], asking `keep_going` now and then while it fills the fit's tears, the one step
/// whose work grows with the surface's area in tiles rather than with the tiles laid (a
/// surface far larger than its pattern's tiles asks for a piece per tile of its area);
/// `false` stops that fill with the pieces laid so far ([`Finished::tear_fill_stopped`]),
/// and the rest (cut list, laying order) is done as usual. The fit's tears are not filled
/// over the `excluded` quads (the pattern's, see [`ExcludedArea`]).
pub fn finish_with(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    tiles: Vec<Tile>,
    spec: &TileSpec,
    options: &FinishOptions,
    excluded: Option<&ExcludedArea>,
    keep_going: &mut dyn FnMut() -> bool,
) -> (Vec<Tile>, Finished) {
    let reference = surface.unwrap_or(quads);
    let cell = spec.length.max(spec.width);
    let boundary = if options.creases {
        SurfaceBoundary::with_creases(reference, cell, spec.joint / 2.0)
    } else {
        SurfaceBoundary::new(reference, cell)
    };
    let half_blank = [spec.length / 2.0, spec.width, spec.thickness];
    let seeds = if options.fit.is_some() {
        fill::Seeds::Tiles { joint: spec.joint }
    } else {
        fill::Seeds::Quads
    };
    let fillers = fill::fill(quads, &tiles, &boundary, half_blank, seeds);
    let fillers_from = tiles.len();
    let mut parents = vec![None; tiles.len()];
    parents.extend(fillers.iter().map(|f| Some(f.parent)));
    let mut windows = vec![None; tiles.len()];
    windows.extend(fillers.iter().map(|f| Some(f.cell)));
    let candidates = tiles.into_iter().chain(fillers.into_iter().map(|f| f.tile));

    let mut kept = Vec::with_capacity(parents.len());
    let mut kept_index = vec![None; parents.len()];
    let mut dropped = Vec::new();
    // After the fit, filler pieces are cut to the room the tiles (and the pieces before them)
    // leave, not to their cells: the cells continue the tiles' footprints, which no longer
    // meet where the fit moved the tiles apart or together.
    let room = options.fit.is_some();
    let reach = spec.length.hypot(spec.width) + spec.joint;
    let mut placed = crate::geom::HashGrid::new(reach);
    let mut outlines: Vec<Vec<Point3<f64>>> = Vec::new();
    for (i, mut tile) in candidates.enumerate() {
        let drop = |tile: &Tile, reason, kept_area, kept_width| DroppedTile {
            faces: tile.faces.clone(),
            reason,
            kept_area,
            kept_width,
        };
        let mut clipped = boundary.clip(&tile, options.tolerance);
        if let (Some(window), false) = (&windows[i], room) {
            // A filler piece stays on its own cell.
            let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
            let rect = vec![vec![[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]]];
            let loops = match &clipped {
                clip::Clipped::Cut(cut) => &cut.loops,
                _ => &rect,
            };
            if !matches!(clipped, clip::Clipped::Outside) {
                clipped = match Cut::within(loops, window, 4.0 * hx * hy) {
                    Some(cut) if cut.kept_fraction < 1.0 - 1e-9 => clip::Clipped::Cut(cut),
                    Some(_) => clip::Clipped::Whole,
                    None => clip::Clipped::Outside,
                };
            }
        }
        match clipped {
            clip::Clipped::Whole => {}
            // Fillers that reach nothing are not placed at all (the fill only keeps cells that
            // touch the surface, but a cell can touch it only within the tolerance).
            clip::Clipped::Outside if i >= fillers_from => continue,
            clip::Clipped::Outside => {
                dropped.push(drop(&tile, DropReason::Outside, 0.0, 0.0));
                continue;
            }
            clip::Clipped::Cut(cut) => {
                if cut.kept_width() < options.min_kept_width {
                    // A sliver of a filler is the strip between the quad mesh and the edge:
                    // too thin for a piece, it is mortar (and shows in the coverage).
                    if i < fillers_from {
                        dropped.push(drop(
                            &tile,
                            DropReason::Sliver,
                            cut.area(),
                            cut.kept_width(),
                        ));
                    }
                    continue;
                }
                tile.kind = TileKind::Boundary;
                tile.cut = Some(cut);
            }
        }
        if room && i >= fillers_from {
            let near = placed.near(&tile.frame.origin, reach);
            if !fit::cut_to_room(&mut tile, &kept, &outlines, &near, spec.joint) {
                continue;
            }
            if let Some(cut) = &tile.cut {
                if cut.kept_width() < options.min_kept_width {
                    continue;
                }
                tile.kind = TileKind::Boundary;
            }
        }
        kept_index[i] = Some(kept.len());
        if room {
            placed.insert(kept.len(), &tile.frame.origin, &tile.frame.origin);
            outlines.push(outline::world_corners(&tile));
        }
        kept.push(tile);
    }
    // What the fit could not make fit is cut (after the boundary cut, so that filler pieces
    // and cut outlines take part); a piece left too narrow is a sliver like any other.
    if let Some(fit) = &options.fit {
        // A tile tapped over instead of cut must stay whole on the surface.
        let stays_whole =
            |t: &Tile| matches!(boundary.clip(t, options.tolerance), clip::Clipped::Whole);
        let cut = fit::resolve_overlaps_nudging(
            &mut kept,
            spec.joint,
            fit.overlap_tolerance,
            &stays_whole,
        );
        // A closer the fit left room enough for stays whole: no cut to fit.
        for (t, tile) in kept.iter_mut().enumerate() {
            if tile.fit_cut && !cut.contains(&t) {
                tile.fit_cut = false;
            }
        }
        let slivers: Vec<usize> = cut
            .into_iter()
            .filter(|&t| {
                kept[t]
                    .cut
                    .as_ref()
                    .is_some_and(|c| c.kept_width() < options.min_kept_width)
            })
            .collect();
        if !slivers.is_empty() {
            let mut keep = vec![true; kept.len()];
            for &t in &slivers {
                keep[t] = false;
                let c = kept[t].cut.as_ref().expect("cut");
                if !kept[t].faces.is_empty() {
                    dropped.push(DroppedTile {
                        faces: kept[t].faces.clone(),
                        reason: DropReason::Sliver,
                        kept_area: c.area(),
                        kept_width: c.kept_width(),
                    });
                }
            }
            // Renumber: parents and kept indices refer to positions in `kept`.
            let mut renumber = vec![None; kept.len()];
            let mut next = 0;
            for (t, k) in keep.iter().enumerate() {
                if *k {
                    renumber[t] = Some(next);
                    next += 1;
                }
            }
            for slot in kept_index.iter_mut() {
                *slot = slot.and_then(|k| renumber[k]);
            }
            let mut keeps = keep.iter();
            kept.retain(|_| *keeps.next().expect("one flag per tile"));
        }
    }
    // Tears the fit left wide enough for a piece are filled like the strip along the edge.
    let tears = if options.fit.is_some() {
        tears::Tears {
            surface: reference,
            boundary: &boundary,
            blank: [spec.length, spec.width, spec.thickness],
            joint: spec.joint,
            min_width: options.min_kept_width,
            tolerance: options.tolerance,
            excluded,
        }
        .fill(&mut kept, keep_going)
    } else {
        tears::Filled {
            pieces: 0,
            inside_cuts: 0,
            halves: 0,
            stopped: false,
        }
    };
    let mut links: Vec<[usize; 2]> = parents
        .iter()
        .enumerate()
        .filter_map(|(i, p)| Some([kept_index[i]?, kept_index[(*p)?]?]))
        .collect();
    links.extend(loose_neighbours(quads, &kept));
    // Whole pieces the fit laid in the rooms of its courses (tiles on no quad among those it
    // placed, [`fit`]'s rooms) fill its tears as the tear fill's whole halves do, and are
    // counted with them.
    let rooms: Vec<&Tile> = kept_index[..fillers_from]
        .iter()
        .flatten()
        .map(|&k| &kept[k])
        .filter(|t| t.faces.is_empty())
        .collect();
    let room_halves = rooms
        .iter()
        .filter(|t| t.kind == TileKind::Half && t.cut.is_none())
        .count();
    let room_pieces = rooms.len();
    let fillers = kept_index[fillers_from..].iter().flatten().count() + tears.pieces + room_pieces;
    let cut_list = cutlist::cut_list(&mut kept, options.tolerance);
    let sequence = sequence::laying_order(quads, &mut kept, &links, &options.sequence);
    let lifts = lifts(&kept, &boundary);
    (
        kept,
        Finished {
            dropped,
            fillers,
            tear_pieces: tears.pieces + room_pieces,
            tear_cuts: tears.inside_cuts,
            tear_halves: tears.halves + room_halves,
            tear_fill_stopped: tears.stopped,
            cut_list,
            sequence,
            lifts,
        },
    )
}

/// How far each tile stands off the surface it is laid on: the largest distance from the
/// surface (of the tile's own sheet, [`SurfaceBoundary::sheet_of`]) of its bottom face's kept
/// corners. A flat tile on a surface of radius `R` stands off by about `(L^2 + W^2) / 8R` at
/// its corners by itself (6 mm for 280 x 140 mm at 1.6 m); much more means the surface turns
/// under it where the quads did not (a crease across the input's triangles, facets coarser
/// than a tile). A tile with no surface within its diagonal counts that far.
pub(crate) fn lifts(tiles: &[Tile], boundary: &SurfaceBoundary) -> Vec<f64> {
    crate::parallel::map(tiles.len(), |t| {
        let tile = &tiles[t];
        let reach = tile.size[0].hypot(tile.size[1]);
        let sheet = boundary.sheet_of(tile, reach);
        boundary.lift(&outline::world_outline(tile), reach, sheet)
    })
}

/// Why tiles could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum TileError {
    /// A tile dimension or finishing option is out of range.
    #[error(
        "tile option {name} {value} must be a finite number > 0 (joint, tolerances and time limits >= 0)"
    )]
    InvalidSpec {
        /// Which dimension.
        name: &'static str,
        /// Its value.
        value: f64,
    },
    /// A dimension out of proportion with the tile: a joint as wide as the tile, a tile
    /// thicker than it is long (usually a unit slip in one number).
    #[error(
        "tile option {name} {value} is not smaller than the tile's {than} {limit}: a {name} is a fraction of the tile (e.g. a 10 mm joint and a 15 mm thickness on a 280 x 140 mm tile); give every tile dimension in the same unit"
    )]
    OutOfProportion {
        /// Which dimension.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The dimension it must be smaller than.
        than: &'static str,
        /// That dimension's value.
        limit: f64,
    },
    /// The up direction of the laying order is zero or not finite.
    #[error(
        "the up direction {up:?} is no direction (it must be finite and not zero): give the model's up as x,y,z, e.g. 0,0,1 (Rhino's world Z) or 0,1,0 for a Y-up export"
    )]
    NoUpDirection {
        /// The direction given.
        up: [f64; 3],
    },
    /// The tile is longer than the whole mesh.
    #[error(
        "tile length {length} is larger than the whole mesh (bounding-box diagonal {diagonal}); are the tile and the mesh in the same units?"
    )]
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

impl TileError {
    /// The error with the faces it names numbered as in the file `numbering` traces (the
    /// caller's own numbers, where reading removed faces).
    pub fn in_file_numbers(self, numbering: &crate::mesh::FileNumbering) -> Self {
        let f = |face: usize| numbering.file_face_or_same(face);
        match self {
            TileError::NotAdjacent { a, b } => TileError::NotAdjacent { a: f(a), b: f(b) },
            TileError::FaceUsedTwice { face } => TileError::FaceUsedTwice { face: f(face) },
            TileError::NotQuad { face, corners } => TileError::NotQuad {
                face: f(face),
                corners,
            },
            other => other,
        }
    }
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
        return Err(TileError::TileLargerThanMesh {
            length: spec.length,
            diagonal,
        });
    }
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut used = vec![false; mesh.face_count()];
    let mut claim = |f: usize| -> Result<(), TileError> {
        let slot = used.get_mut(f).ok_or(TileError::FaceOutOfRange {
            face: f,
            face_count: mesh.face_count(),
        })?;
        if std::mem::replace(slot, true) {
            return Err(TileError::FaceUsedTwice { face: f });
        }
        if !mesh.is_quad(f) {
            return Err(TileError::NotQuad {
                face: f,
                corners: mesh.faces()[f].len(),
            });
        }
        Ok(())
    };

    let mut tiles = Vec::with_capacity(pattern.pairs.len() + pattern.unpaired.len());
    for &[a, b] in &pattern.pairs {
        claim(a)?;
        claim(b)?;
        let adjacent = topology
            .face_edges(a)
            .iter()
            .any(|&e| topology.edges()[e].other_face(a) == Some(b));
        if !adjacent {
            return Err(TileError::NotAdjacent { a, b });
        }
        let frame = Frame::for_pair(mesh, a, b);
        tiles.push(Tile::new(
            TileKind::Full,
            vec![a, b],
            frame,
            [spec.length, spec.width, spec.thickness],
        ));
    }
    for &f in &pattern.unpaired {
        claim(f)?;
        let frame = Frame::for_face(mesh, f);
        tiles.push(Tile::new(
            TileKind::Half,
            vec![f],
            frame,
            [spec.length / 2.0, spec.width, spec.thickness],
        ));
    }
    Ok(tiles)
}

/// Pairs of tiles the quad mesh does not join but that rest against each other: at least one
/// of them a filler piece (no faces), or the two on different pieces of the quad mesh (the
/// sheets of a surface cut open at its creases, whose webs lean on each other along a groin),
/// whose centres are no further apart than their blanks' half lengths and widths plus a
/// margin.
fn loose_neighbours(quads: &PolyMesh, tiles: &[Tile]) -> Vec<[usize; 2]> {
    let reach = tiles
        .iter()
        .map(|t| t.size[0].max(t.size[1]))
        .fold(0.0, f64::max)
        * 1.25;
    if reach <= 0.0 {
        return Vec::new();
    }
    let (piece_of_face, pieces) = Topology::new(quads)
        .expect("a PolyMesh is manifold by construction")
        .face_pieces();
    let piece = |t: &Tile| t.faces.first().map(|&f| piece_of_face[f]);
    let grid = crate::geom::HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin]));
    let mut links = Vec::new();
    for (i, t) in tiles.iter().enumerate() {
        let own = piece(t);
        if own.is_some() && pieces < 2 {
            continue;
        }
        for j in grid.near(&t.frame.origin, reach) {
            let u = &tiles[j];
            let loose = match (own, piece(u)) {
                // A filler and a tile on quads: once, from the filler.
                (None, Some(_)) => true,
                (None, None) => j > i,
                (Some(a), Some(b)) => a != b && j > i,
                (Some(_), None) => false,
            };
            let close =
                (u.frame.origin - t.frame.origin).norm() <= (t.size[0] + u.size[0]) / 2.0 * 1.25;
            if j != i && close && loose {
                links.push([i, j]);
            }
        }
    }
    links
}

/// The corners of a box of `size` on `frame` ([`Tile::corners`]' order).
fn box_corners(frame: &Frame, size: [f64; 3]) -> [[f64; 3]; 8] {
    let [l, w, t] = size;
    let corner = |sx: f64, sy: f64, z: f64| -> [f64; 3] {
        let p: Point3<f64> =
            frame.origin + frame.x * (sx * l / 2.0) + frame.y * (sy * w / 2.0) + frame.z * z;
        [p.x, p.y, p.z]
    };
    let square = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut corners = [[0.0; 3]; 8];
    for (k, (sx, sy)) in square.iter().enumerate() {
        corners[k] = corner(*sx, *sy, 0.0);
        corners[k + 4] = corner(*sx, *sy, t);
    }
    corners
}

impl Tile {
    /// Places the tile on `frame`, its box corners with it (its outline, in the frame, stays).
    pub(crate) fn move_to(&mut self, frame: Frame) {
        self.corners = box_corners(&frame, self.size);
        self.frame = frame;
    }

    pub(crate) fn new(kind: TileKind, faces: Vec<usize>, frame: Frame, size: [f64; 3]) -> Self {
        Self {
            kind,
            faces,
            corners: box_corners(&frame, size),
            frame,
            size,
            cut: None,
            label: String::new(),
            step: 0,
            fit_cut: false,
        }
    }

    /// Area of the tile's face that is kept: all of it unless it was cut.
    pub fn kept_area(&self) -> f64 {
        self.cut
            .as_ref()
            .map_or(self.size[0] * self.size[1], Cut::area)
    }

    /// Position of a point given in the tile's frame.
    pub fn to_world(&self, local: Vector3<f64>) -> Point3<f64> {
        self.frame.origin + self.frame.x * local.x + self.frame.y * local.y + self.frame.z * local.z
    }
}

/// Formats tiles as OBJ: one object per tile named `full_<i>`, `half_<i>`, `boundary_<i>`
/// (cut to the surface's boundary, filler pieces included) or `fitcut_<i>` (cut by the fit
/// stage), `i` = tile index; each the tile's [`solid::solid`]: a box, or for a cut tile the
/// prisms of its kept pieces, outward-facing.
pub fn to_obj(tiles: &[Tile]) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let mut next = 1;
    for (i, tile) in tiles.iter().enumerate() {
        let kind = match tile.kind {
            TileKind::Full => "full",
            TileKind::Half => "half",
            TileKind::Boundary => "boundary",
            TileKind::FitCut => "fitcut",
        };
        let _ = writeln!(out, "o {kind}_{i}");
        let piece = solid::solid(tile);
        for p in &piece.positions {
            let _ = writeln!(out, "v {} {} {}", p.x, p.y, p.z);
        }
        for face in &piece.faces {
            let ids: Vec<String> = face.iter().map(|k| (next + k).to_string()).collect();
            let _ = writeln!(out, "f {}", ids.join(" "));
        }
        next += piece.positions.len();
    }
    out
}

#[cfg(test)]
mod tests {
    use nalgebra::{Point3, Vector3};

    use super::*;
    use crate::mesh::generate;

    /// A full tile of 1.9 x 0.9 on faces `faces`, centred at (x, 0.5).
    fn tile_at(faces: Vec<usize>, x: f64) -> Tile {
        let frame = Frame {
            origin: Point3::new(x, 0.5, 0.0),
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        };
        Tile::new(TileKind::Full, faces, frame, [1.9, 0.9, 0.1])
    }

    #[test]
    fn tiles_of_two_sheets_side_by_side_rest_on_each_other() {
        // Two rows of two unit quads a centimetre apart: the sheets of a surface cut open at
        // a crease, which no mesh edge joins.
        let row = |x0: f64| {
            (0..3).flat_map(move |i| [0.0, 1.0].map(|y| Point3::new(x0 + f64::from(i), y, 0.0)))
        };
        let positions: Vec<_> = row(0.0).chain(row(2.01)).collect();
        let quad =
            |o: usize, i: usize| vec![o + 2 * i, o + 2 * i + 2, o + 2 * i + 3, o + 2 * i + 1];
        let sheets = PolyMesh::new(
            positions,
            vec![quad(0, 0), quad(0, 1), quad(6, 0), quad(6, 1)],
        )
        .unwrap();
        let tiles = [tile_at(vec![0, 1], 1.0), tile_at(vec![2, 3], 3.01)];
        assert_eq!(loose_neighbours(&sheets, &tiles), vec![[0, 1]]);
        // On one sheet the shared mesh edge joins them; nothing loose.
        let joined = generate::grid(4, 1);
        let tiles = [tile_at(vec![0, 1], 1.0), tile_at(vec![2, 3], 3.0)];
        assert!(loose_neighbours(&joined, &tiles).is_empty());
    }
}
