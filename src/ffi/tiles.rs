//! Stage 3 and the report through the C ABI.

use std::ffi::c_char;

use super::status::{Failure, TpStatus, guard};
use super::{TpMesh, TpPattern, borrow, hand_over, output, output_text, read_options, release, write_out};
use crate::pipeline::{self, Tiling};
use crate::tiles::{TileKind, TileSpec};

/// Tile kind: a standard tile over two faces.
pub const TP_TILE_FULL: i32 = 0;
/// Tile kind: a half tile over one unmatched quad (needs a cut).
pub const TP_TILE_HALF: i32 = 1;
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
}

/// Placed tiles and their report (opaque).
pub struct TpTiles {
    tiling: Tiling,
}

/// The default tile options (280 x 140 x 15 mm tiles, 10 mm joint, in metres).
#[unsafe(no_mangle)]
pub extern "C" fn tp_tile_options_default() -> TpTileOptions {
    TpTileOptions { struct_size: size_of::<TpTileOptions>() as u32, length: 0.28, width: 0.14, thickness: 0.015, joint: 0.01 }
}

/// Builds the tiles of `pattern` on `mesh` (the mesh the pattern was solved on): full tiles in
/// pair order, then half tiles in face order, and their report.
///
/// # Safety
/// `mesh` and `pattern` must be live handles, `options` valid, `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_build(mesh: *const TpMesh, pattern: *const TpPattern, options: *const TpTileOptions, out: *mut *mut TpTiles) -> TpStatus {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        // SAFETY: live handles and valid options by the caller's promise.
        let (mesh, pattern, raw) =
            unsafe { (&borrow(mesh, "mesh")?.mesh, &borrow(pattern, "pattern")?.pattern, read_options(options, tp_tile_options_default(), "options")?) };
        let spec = TileSpec { length: raw.length, width: raw.width, thickness: raw.thickness, joint: raw.joint };
        let tiling = pipeline::tiles_for_pattern(mesh, pattern.clone(), &spec)?;
        // SAFETY: checked non-null above.
        unsafe { hand_over(out, TpTiles { tiling }, "out") }
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
unsafe fn copy_per_tile<T: Copy>(tiles: *const TpTiles, out: *mut T, capacity: usize, values: impl Fn(&crate::tiles::Tile) -> Vec<T>) -> TpStatus {
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
pub unsafe extern "C" fn tp_tiles_copy_kinds(tiles: *const TpTiles, out: *mut i32, capacity: usize) -> TpStatus {
    let kind = |t: &crate::tiles::Tile| vec![if t.kind == TileKind::Full { TP_TILE_FULL } else { TP_TILE_HALF }];
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, kind) }
}

/// Copies each tile's 8 box corners as xyz (24 doubles per tile): the bottom face
/// counter-clockwise from (-x, -y), then the top face in the same order.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_corners(tiles: *const TpTiles, out: *mut f64, capacity: usize) -> TpStatus {
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, |t| t.corners.iter().flatten().copied().collect()) }
}

/// Copies each tile's frame (12 doubles per tile): origin, length axis x, height axis y,
/// thickness axis z, each as xyz. The box spans `[-L/2, L/2] x [-W/2, W/2] x [0, T]` in it.
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_frames(tiles: *const TpTiles, out: *mut f64, capacity: usize) -> TpStatus {
    let frame = |t: &crate::tiles::Tile| {
        let f = &t.frame;
        [f.origin.coords, f.x, f.y, f.z].iter().flat_map(|v| [v.x, v.y, v.z]).collect()
    };
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, frame) }
}

/// Copies each tile's box size: length, width, thickness (3 doubles per tile).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_sizes(tiles: *const TpTiles, out: *mut f64, capacity: usize) -> TpStatus {
    // SAFETY: forwarded.
    unsafe { copy_per_tile(tiles, out, capacity, |t| t.size.to_vec()) }
}

/// Copies the faces each tile covers (2 per tile; `TP_NO_FACE` in the second slot of a half
/// tile).
///
/// # Safety
/// `tiles` must be a live handle and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_tiles_copy_faces(tiles: *const TpTiles, out: *mut u32, capacity: usize) -> TpStatus {
    let faces = |t: &crate::tiles::Tile| vec![t.faces[0] as u32, t.faces.get(1).map_or(TP_NO_FACE, |&f| f as u32)];
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
pub unsafe extern "C" fn tp_tiles_report_json(tiles: *const TpTiles, buf: *mut c_char, len: usize, needed: *mut usize) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let tiling = &unsafe { borrow(tiles, "tiles") }?.tiling;
        let json = serde_json::to_string_pretty(&tiling.report).map_err(|e| Failure::new(TpStatus::TP_PANIC, e.to_string()))?;
        // SAFETY: forwarded.
        unsafe { output_text(&json, buf, len, needed) }
    })
}
