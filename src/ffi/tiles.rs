//! Stage 3 and the report through the C ABI.

use std::ffi::{c_char, c_void};

use super::status::{Failure, TpStatus, guard};
use super::{
    TP_STAGE_TILES, TpMesh, TpPattern, TpProgressCallback, borrow, hand_over, init_options, output,
    output_text, progress_reporter, read_options, release, write_out,
};
use crate::control::Control;
use crate::pattern::Bond;
use crate::pipeline::{self, Tiling};
use crate::report::WarningCode;
use crate::tiles::{
    FinishOptions, FitOptions, FitStatus, SequenceOptions, Tile, TileKind, TileSpec,
};

/// Tile kind: a standard tile over two faces.
pub const TP_TILE_FULL: i32 = 0;
/// Tile kind: a half tile over one unmatched quad (needs a cut).
pub const TP_TILE_HALF: i32 = 1;
/// Tile kind: a full or half tile cut to the surface's boundary (see
/// [`tp_tiles_copy_loop_points`]).
pub const TP_TILE_BOUNDARY: i32 = 2;
/// Tile kind: a full or half tile cut by the fit stage where it could not be made to fit its
/// neighbours (its outline is read like a boundary tile's).
pub const TP_TILE_FIT_CUT: i32 = 3;
/// Face slot of a half tile's missing second face in [`tp_tiles_copy_faces`].
pub const TP_NO_FACE: u32 = u32::MAX;

/// Tile dimensions in model units. Initialise with [`tp_tile_options_default`].
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpTileOptions {
    /// `sizeof(TpTileOptions)` as compiled by the caller; set by the default initialiser.
    pub struct_size: u32,
    /// Tile length; default 0.28 (a 280 mm tile in metres).
    pub length: f64,
    /// Tile width; default 0.14.
    pub width: f64,
    /// Tile thickness; default 0.015.
    pub thickness: f64,
    /// Mortar joint; default 0.01.
    pub joint: f64,
    /// Cutting tolerance: tiles the boundary enters by no more than this stay whole, cut
    /// shapes this close share a cut-list label. Negative (default): 1 % of the width.
    pub cut_tolerance: f64,
    /// Boundary pieces narrower than this are slivers: reported, not emitted. Negative
    /// (default): a fifth of the width.
    pub min_kept_width: f64,
    /// Up direction for the laying order, xyz; default (0, 0, 1).
    pub up: [f64; 3],
    /// Tiles with a boundary edge within this height of the lowest boundary point stand on
    /// the supports. Negative (default): one tile width.
    pub support_band: f64,
    /// Non-zero (default): the fit stage moves the tiles on the surface so that joints come
    /// close to `joint`, and cuts what cannot fit; zero keeps the paper's placement (section
    /// 3.5). Since ABI 3.
    pub fit: i32,
    /// Wall-clock limit of the fit stage in seconds; default 10. When it passes the best
    /// placement so far is kept (the report's `fit.status` says `time_limit`). The same limit
    /// holds again for filling the fit's tears with pieces; when it passes, the pieces laid so
    /// far are kept and `fit.status` says `time_limit`. It also sizes, by a count of work and
    /// not the clock, the largest first placement a second one (with closers) may follow, so
    /// that the same input gives the same tiles on any machine. Since ABI 3.
    pub fit_time_limit_seconds: f64,
    /// Overlaps the fit stage leaves; deeper ones are cut. Negative (default): a twentieth of
    /// the joint, at least a three-hundredth of the tile's width. Since ABI 3.
    pub fit_overlap_tolerance: f64,
    /// How far the fit may move a running bond's half offset or an aligned joint. Negative
    /// (default): a tenth of the tile length. Since ABI 3.
    pub fit_bond_tolerance: f64,
    /// Model units per millimetre, for the report's figures in millimetres (the share of
    /// joints within 2 and 5 mm); default 0.001 (a model in metres). Since ABI 3.
    pub units_per_mm: f64,
    /// Non-zero (default): the creases that part the surface into sheets (a groin vault's
    /// groins) are cut to like a boundary, half a joint short on each side, and tiles and
    /// filler pieces stay on their own sheet; zero takes the surface as one sheet. Pair it
    /// with `TpRemeshOptions.creases`. Since ABI 7.
    pub creases: i32,
}

impl TpTileOptions {
    pub(super) fn spec(&self) -> TileSpec {
        TileSpec {
            length: self.length,
            width: self.width,
            thickness: self.thickness,
            joint: self.joint,
        }
    }

    /// The finishing options, negative values replaced by their defaults for the tile; the fit
    /// keeps `bond`.
    pub(super) fn finish(&self, bond: Bond) -> FinishOptions {
        let auto = FinishOptions::for_spec(&self.spec());
        let or_auto = |value: f64, default: f64| if value < 0.0 { default } else { value };
        let fit = auto.fit.filter(|_| self.fit != 0).map(|fit| FitOptions {
            bond,
            time_limit: self.fit_time_limit_seconds,
            overlap_tolerance: or_auto(self.fit_overlap_tolerance, fit.overlap_tolerance),
            bond_tolerance: or_auto(self.fit_bond_tolerance, fit.bond_tolerance),
            ..fit
        });
        FinishOptions {
            tolerance: or_auto(self.cut_tolerance, auto.tolerance),
            min_kept_width: or_auto(self.min_kept_width, auto.min_kept_width),
            sequence: SequenceOptions {
                up: nalgebra::Vector3::from(self.up),
                support_band: or_auto(self.support_band, auto.sequence.support_band),
            },
            fit,
            units_per_mm: self.units_per_mm,
            creases: self.creases != 0,
        }
    }
}

/// Placed tiles and their report (opaque).
pub struct TpTiles {
    pub(super) tiling: Tiling,
}

/// The default tile options (280 x 140 x 15 mm tiles, 10 mm joint, in metres).
#[unsafe(no_mangle)]
pub extern "C" fn tp_tile_options_default() -> TpTileOptions {
    TpTileOptions {
        struct_size: size_of::<TpTileOptions>() as u32,
        length: 0.28,
        width: 0.14,
        thickness: 0.015,
        joint: 0.01,
        cut_tolerance: -1.0,
        min_kept_width: -1.0,
        up: [0.0, 0.0, 1.0],
        support_band: -1.0,
        fit: 1,
        fit_time_limit_seconds: 10.0,
        fit_overlap_tolerance: -1.0,
        fit_bond_tolerance: -1.0,
        units_per_mm: 0.001,
        creases: 1,
    }
}

/// Fills `*options`, a `TpTileOptions` of `size` bytes (pass `sizeof *options`), with the
/// defaults. Prefer this to [`tp_tile_options_default`] in code that may load a newer library: it
/// never writes more than `size` bytes.
///
/// # Safety
/// `options` must point to `size` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tile_options_init(
    options: *mut TpTileOptions,
    size: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    guard(|| unsafe { init_options(options, size, tp_tile_options_default(), "options") })
}

/// Builds the tiles of `pattern` on `mesh` (the mesh the pattern was solved on): full tiles in
/// pair order, then half tiles in face order, cut to the mesh's own boundary, labelled and
/// numbered in laying order, and their report. Same as [`tp_tiles_build_on_surface`] without
/// a surface.
///
/// # Safety
/// `mesh` and `pattern` must be live handles, `options` valid, `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_build(
    mesh: *const TpMesh,
    pattern: *const TpPattern,
    options: *const TpTileOptions,
    out: *mut *mut TpTiles,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe { tp_tiles_build_on_surface(mesh, pattern, std::ptr::null(), options, out) }
}

/// Builds the tiles of `pattern` on the quad mesh `mesh` and cuts them to the boundary of
/// `surface`, the input surface the quads were made from (outer edge and openings; NULL: the
/// quad mesh's own boundary). Tiles off the surface and slivers are left out and counted in
/// the report.
///
/// # Safety
/// `mesh` and `pattern` must be live handles, `surface` NULL or a live handle, `options`
/// valid, `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_build_on_surface(
    mesh: *const TpMesh,
    pattern: *const TpPattern,
    surface: *const TpMesh,
    options: *const TpTileOptions,
    out: *mut *mut TpTiles,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe {
        tp_tiles_build_with_progress(
            mesh,
            pattern,
            surface,
            options,
            None,
            std::ptr::null_mut(),
            out,
        )
    }
}

/// [`tp_tiles_build_on_surface`] reporting the fit stage's progress: `progress` (may be NULL)
/// is called with `TP_STAGE_TILES` and the share of the fit's step limit used (1 when the fit
/// is done); a non-zero return cancels the fit and the call returns `TP_CANCELLED` without
/// tiles (the Rust API keeps the placement so far, with `fit.status` `cancelled`).
///
/// # Safety
/// As [`tp_tiles_build_on_surface`]; `user` is passed to `progress` untouched.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_build_with_progress(
    mesh: *const TpMesh,
    pattern: *const TpPattern,
    surface: *const TpMesh,
    options: *const TpTileOptions,
    progress: TpProgressCallback,
    user: *mut c_void,
    out: *mut *mut TpTiles,
) -> TpStatus {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        // SAFETY: live handles and valid options by the caller's promise.
        let (mesh, pattern, raw) = unsafe {
            (
                &borrow(mesh, "mesh")?.mesh,
                borrow(pattern, "pattern")?,
                read_options(options, tp_tile_options_default(), "options")?,
            )
        };
        // SAFETY: NULL or a live handle by the caller's promise.
        let surface = if surface.is_null() {
            None
        } else {
            Some(&unsafe { borrow(surface, "surface") }?.mesh)
        };
        let mut report = progress_reporter(progress, user, TP_STAGE_TILES);
        let mut control = Control::with_progress(&mut report);
        let tiling = pipeline::tiles_for_pattern_with(
            mesh,
            surface,
            pattern.pattern.clone(),
            &raw.spec(),
            &raw.finish(pattern.bond),
            &mut control,
        )?;
        if tiling
            .report
            .fit
            .is_some_and(|f| f.status == FitStatus::Cancelled)
        {
            return Err(Failure::new(
                TpStatus::TP_CANCELLED,
                "cancelled by the progress callback during the fit stage",
            ));
        }
        // SAFETY: checked non-null above.
        unsafe { hand_over(out, TpTiles { tiling }, "out") }
    })
}

/// Copies each tile's worst joint: the largest `|gap - joint|` over the joints it takes
/// part in (0 for a tile with none), in model units (capacity: tile count). For a colour
/// preview of the joints.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_joint_deviations(
    tiles: *const TpTiles,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiles = unsafe { borrow(tiles, "tiles") }?;
        let deviations = tiles.tiling.joint_deviations();
        // SAFETY: forwarded.
        unsafe { output(&deviations, out, capacity, "out") }
    })
}

/// Releases tiles. NULL is accepted.
///
/// # Safety
/// `tiles` must be NULL or a live handle, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_free(tiles: *mut TpTiles) {
    // SAFETY: forwarded.
    unsafe { release(tiles) }
}

/// Writes the number of tiles.
///
/// # Safety
/// `tiles` must be a live handle and `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_count(tiles: *const TpTiles, out: *mut usize) -> TpStatus {
    guard(|| {
        // SAFETY: live handle and writable out by the caller's promise.
        unsafe { write_out(out, borrow(tiles, "tiles")?.tiling.tiles.len(), "out") }
    })
}

/// Copies per-tile values, `per_tile` items each, produced by `values`.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
unsafe fn copy_per_tile<T: Copy>(
    tiles: *const TpTiles,
    out: *mut T,
    capacity: usize,
    values: impl Fn(&Tile) -> Vec<T>,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let flat: Vec<T> = tiling.tiles.iter().flat_map(values).collect();
        // SAFETY: capacity as promised.
        unsafe { output(&flat, out, capacity, "out") }
    })
}

/// Copies each tile's kind (`TP_TILE_*`; capacity: tile count).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_kinds(
    tiles: *const TpTiles,
    out: *mut i32,
    capacity: usize,
) -> TpStatus {
    let kind = |t: &Tile| {
        vec![match t.kind {
            TileKind::Full => TP_TILE_FULL,
            TileKind::Half => TP_TILE_HALF,
            TileKind::Boundary => TP_TILE_BOUNDARY,
            TileKind::FitCut => TP_TILE_FIT_CUT,
        }]
    };
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, kind) }
}

/// Copies each tile's 8 box corners as xyz (24 doubles per tile): the bottom face
/// counter-clockwise from (-x, -y), then the top face in the same order.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_corners(
    tiles: *const TpTiles,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe {
        copy_per_tile(tiles, out, capacity, |t| {
            t.corners.iter().flatten().copied().collect()
        })
    }
}

/// Copies each tile's frame (12 doubles per tile): origin, length axis x, height axis y,
/// thickness axis z, each as xyz. The box spans `[-L/2, L/2] x [-W/2, W/2] x [0, T]` in it.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_frames(
    tiles: *const TpTiles,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    let frame = |t: &Tile| {
        let f = &t.frame;
        [f.origin.coords, f.x, f.y, f.z]
            .iter()
            .flat_map(|v| [v.x, v.y, v.z])
            .collect()
    };
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, frame) }
}

/// Copies each tile's box size: length, width, thickness (3 doubles per tile).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_sizes(
    tiles: *const TpTiles,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, |t| t.size.to_vec()) }
}

/// Copies the faces each tile covers (2 per tile; `TP_NO_FACE` in the second slot of a half
/// tile, in both slots of a filler piece beyond the quad mesh's boundary).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_faces(
    tiles: *const TpTiles,
    out: *mut u32,
    capacity: usize,
) -> TpStatus {
    let faces = |t: &Tile| {
        (0..2)
            .map(|k| t.faces.get(k).map_or(TP_NO_FACE, |&f| f as u32))
            .collect()
    };
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, faces) }
}

/// Copies the report (the same JSON as `tilepattern tiles --json`, without `units`) into
/// `buf` as a NUL-terminated string; `*needed` (if not NULL) gets its length without the NUL.
/// Call with `len = 0` to ask for the size.
///
/// # Safety
/// `tiles` must be a live handle, `buf` hold `len` bytes, `needed` be NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_report_json(
    tiles: *const TpTiles,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let json = serde_json::to_string_pretty(&tiling.report)
            .map_err(|e| Failure::new(TpStatus::TP_PANIC, e.to_string()))?;
        // SAFETY: forwarded.
        unsafe { output_text(&json, buf, len, needed) }
    })
}

/// Copies each tile's step in the laying order, from 0 (capacity: tile count).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_steps(
    tiles: *const TpTiles,
    out: *mut u32,
    capacity: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, |t| vec![t.step as u32]) }
}

/// Copies each tile's kept area over its face area: 1 for uncut tiles (capacity: tile count).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_kept_fractions(
    tiles: *const TpTiles,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe {
        copy_per_tile(tiles, out, capacity, |t| {
            vec![t.cut.as_ref().map_or(1.0, |c| c.kept_fraction)]
        })
    }
}

/// Writes the total number of outline loops and of their points over all cut tiles (cut to
/// the boundary, `TP_TILE_BOUNDARY`, or to fit, `TP_TILE_FIT_CUT`): the
/// capacities for [`tp_tiles_copy_loop_sizes`] and (times 2) [`tp_tiles_copy_loop_points`].
/// Either pointer may be NULL.
///
/// # Safety
/// `tiles` must be a live handle, `loops` and `points` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_outline_counts(
    tiles: *const TpTiles,
    loops: *mut usize,
    points: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let all = || {
            tiling
                .tiles
                .iter()
                .flat_map(|t| t.cut.iter().flat_map(|c| &c.loops))
        };
        for (out, value) in [(loops, all().count()), (points, all().map(Vec::len).sum())] {
            if !out.is_null() {
                // SAFETY: non-null and writable by the caller's promise.
                unsafe { write_out(out, value, "count") }?;
            }
        }
        Ok(())
    })
}

/// Copies each tile's number of outline loops: 0 for an uncut tile (capacity: tile count).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_loop_counts(
    tiles: *const TpTiles,
    out: *mut u32,
    capacity: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe {
        copy_per_tile(tiles, out, capacity, |t| {
            vec![t.cut.as_ref().map_or(0, |c| c.loops.len() as u32)]
        })
    }
}

/// Copies the number of points of every outline loop, tile by tile (capacity: the loop
/// count of [`tp_tiles_outline_counts`]).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_loop_sizes(
    tiles: *const TpTiles,
    out: *mut u32,
    capacity: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    unsafe {
        copy_per_tile(tiles, out, capacity, |t| {
            t.cut
                .iter()
                .flat_map(|c| &c.loops)
                .map(|l| l.len() as u32)
                .collect()
        })
    }
}

/// Copies the points of every outline loop as (x, y) in the tile's frame (2 doubles per
/// point), tile by tile and loop by loop: the part of the tile's face to keep, outer loops
/// counter-clockwise, holes clockwise, seen from the frame's +z.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_loop_points(
    tiles: *const TpTiles,
    out: *mut f64,
    capacity: usize,
) -> TpStatus {
    let points = |t: &Tile| {
        t.cut
            .iter()
            .flat_map(|c| &c.loops)
            .flatten()
            .flat_map(|p| *p)
            .collect()
    };
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, points) }
}

/// Copies the tiles' cut-list labels (`F`, `H`, `B1`, ...), one per tile, each followed by a
/// newline, as a NUL-terminated string; `*needed` (if not NULL) gets its length without the
/// NUL. Call with `len = 0` to ask for the size.
///
/// # Safety
/// `tiles` must be a live handle, `buf` hold `len` bytes, `needed` be NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_labels(
    tiles: *const TpTiles,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let text: String = tiling
            .tiles
            .iter()
            .map(|t| format!("{}\n", t.label))
            .collect();
        // SAFETY: forwarded.
        unsafe { output_text(&text, buf, len, needed) }
    })
}

/// Copies the cut list (the same JSON as `cutlist.json` of `tilepattern run`) into `buf` as
/// a NUL-terminated string; `*needed` (if not NULL) gets its length without the NUL.
///
/// # Safety
/// `tiles` must be a live handle, `buf` hold `len` bytes, `needed` be NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_cutlist_json(
    tiles: *const TpTiles,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let json = serde_json::to_string_pretty(&tiling.cut_list)
            .map_err(|e| Failure::new(TpStatus::TP_PANIC, e.to_string()))?;
        // SAFETY: forwarded.
        unsafe { output_text(&json, buf, len, needed) }
    })
}

/// Why a tiling deserves a second look (`report.json`'s `warnings[].code`, by number). The
/// numbers are stable: new codes get new numbers, none is reused.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TpWarning {
    /// The surface has no boundary (a sphere, a torus, a box).
    TP_WARNING_CLOSED_SURFACE = 1,
    /// The surface falls into several pieces that share no edge.
    TP_WARNING_SEVERAL_PIECES = 2,
    /// Most face normals point down: tiles are laid on the underside.
    TP_WARNING_NORMALS_DOWN = 3,
    /// The tile does not fit the half-tile model (length about 2 x width + joint).
    TP_WARNING_TILE_SHAPE = 4,
    /// The surface turns a lot over one tile length.
    TP_WARNING_TILE_VS_CURVATURE = 5,
    /// The tiles cover less than 0.95 of the surface.
    TP_WARNING_LOW_COVERAGE = 6,
    /// Tiles were left out (off the surface, or slivers).
    TP_WARNING_TILES_DROPPED = 7,
    /// Nothing to lay from: a closed surface, or a level one on the ground.
    TP_WARNING_NO_SUPPORT = 8,
    /// Reading a file joined coincident vertices.
    TP_WARNING_VERTICES_WELDED = 9,
    /// The fit stage cut more than 1 % of the tiles (courses converge or diverge).
    TP_WARNING_FIT_CUTS = 10,
    /// The joints' p95 deviation from the nominal joint is more than half the joint.
    TP_WARNING_WIDE_JOINTS = 11,
    /// The surface folds back on itself (neighbouring faces turned by more than 120 degrees).
    TP_WARNING_FOLDED_SURFACE = 12,
    /// Reading the file turned faces over to agree with their neighbours (the command line;
    /// a host's meshes are taken as given).
    TP_WARNING_NORMALS_UNIFIED = 13,
    /// Fewer than 70 % of the quad edges are within 20 % of half a tile.
    TP_WARNING_QUAD_SIZE = 14,
    /// Tiles stand off the surface by more than their thickness (creases across the input's
    /// triangles, facets coarser than a tile).
    TP_WARNING_TILES_OFF_SURFACE = 15,
    /// The surface has openings smaller than a tile (often a face missing from the mesh).
    TP_WARNING_SMALL_OPENINGS = 16,
    /// The surface faces along another axis than up (a model whose up is Y, tiled with up Z).
    TP_WARNING_UP_AXIS = 17,
    /// The quad mesh does not lie on the surface the tiles are cut to (quads made from
    /// another surface, or the surface moved, scaled or in other units since).
    TP_WARNING_QUADS_OFF_SURFACE = 18,
    /// Faces of more than four corners, larger than a tile and not flat: the surface inside
    /// them is a guess.
    TP_WARNING_CURVED_POLYGONS = 19,
}

impl From<WarningCode> for TpWarning {
    fn from(code: WarningCode) -> Self {
        use TpWarning::*;
        match code {
            WarningCode::ClosedSurface => TP_WARNING_CLOSED_SURFACE,
            WarningCode::SeveralPieces => TP_WARNING_SEVERAL_PIECES,
            WarningCode::NormalsDown => TP_WARNING_NORMALS_DOWN,
            WarningCode::TileShape => TP_WARNING_TILE_SHAPE,
            WarningCode::TileVsCurvature => TP_WARNING_TILE_VS_CURVATURE,
            WarningCode::LowCoverage => TP_WARNING_LOW_COVERAGE,
            WarningCode::TilesDropped => TP_WARNING_TILES_DROPPED,
            WarningCode::NoSupport => TP_WARNING_NO_SUPPORT,
            WarningCode::VerticesWelded => TP_WARNING_VERTICES_WELDED,
            WarningCode::FitCuts => TP_WARNING_FIT_CUTS,
            WarningCode::WideJoints => TP_WARNING_WIDE_JOINTS,
            WarningCode::FoldedSurface => TP_WARNING_FOLDED_SURFACE,
            WarningCode::NormalsUnified => TP_WARNING_NORMALS_UNIFIED,
            WarningCode::QuadSize => TP_WARNING_QUAD_SIZE,
            WarningCode::TilesOffSurface => TP_WARNING_TILES_OFF_SURFACE,
            WarningCode::SmallOpenings => TP_WARNING_SMALL_OPENINGS,
            WarningCode::UpAxis => TP_WARNING_UP_AXIS,
            WarningCode::QuadsOffSurface => TP_WARNING_QUADS_OFF_SURFACE,
            WarningCode::CurvedPolygons => TP_WARNING_CURVED_POLYGONS,
        }
    }
}

/// Writes the number of warnings on the tiling (0 when all is well): odd input or results to
/// look at twice, the same as `report.json`'s `warnings`.
///
/// # Safety
/// `tiles` must be a live handle and `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_warning_count(
    tiles: *const TpTiles,
    out: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle and writable out by the caller's promise.
        unsafe {
            write_out(
                out,
                borrow(tiles, "tiles")?.tiling.report.warnings.len(),
                "out",
            )
        }
    })
}

/// Copies the warnings' codes (`TP_WARNING_*`; capacity: warning count).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_warning_codes(
    tiles: *const TpTiles,
    out: *mut TpWarning,
    capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let codes: Vec<TpWarning> = tiling
            .report
            .warnings
            .iter()
            .map(|w| w.code.into())
            .collect();
        // SAFETY: capacity as promised.
        unsafe { output(&codes, out, capacity, "out") }
    })
}

/// Copies the warnings' messages (what was found and what to do), one per warning in the
/// order of [`tp_tiles_copy_warning_codes`], each followed by a newline, as a NUL-terminated
/// string; `*needed` (if not NULL) gets its length without the NUL. Call with `len = 0` to
/// ask for the size.
///
/// # Safety
/// `tiles` must be a live handle, `buf` hold `len` bytes, `needed` be NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_warnings(
    tiles: *const TpTiles,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let text: String = tiling
            .report
            .warnings
            .iter()
            .map(|w| format!("{}\n", w.message.replace('\n', " ")))
            .collect();
        // SAFETY: forwarded.
        unsafe { output_text(&text, buf, len, needed) }
    })
}
