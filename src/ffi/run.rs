//! The whole pipeline through the C ABI: the three stages on a few quad meshes of a surface,
//! keeping the tiles that fit best ([`crate::pipeline::tile_surface_tries`]), as the command
//! line's `run` does.

use std::ffi::c_void;

use super::status::{Failure, TpStatus, guard};
use super::{
    TP_STAGE_RUN, TpMesh, TpPattern, TpPatternOptions, TpProgressCallback, TpRemeshOptions,
    TpTileOptions, TpTiles, borrow, hand_over, init_options, pattern::pattern_options,
    progress_reporter, read_options, remesh::remesh_options, tp_pattern_options_default,
    tp_remesh_options_default, tp_tile_options_default,
};
use crate::control::{Control, Figures};
use crate::pipeline::{self, MAX_TRIES, Tries};

/// Options of [`tp_run`] beyond those of the three stages. Initialise with
/// [`tp_run_options_default`] or [`tp_run_options_init`]. Since ABI 9.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpRunOptions {
    /// `sizeof(TpRunOptions)` as compiled by the caller; set by the default initialiser.
    pub struct_size: u32,
    /// How many quad meshes to carry through to tiles: 0 (default) for the command line's
    /// choice (all when the surface needs at most 10,000 quads of `target_edge`, otherwise
    /// 1), or 1 to 6: the remesh options' `renormalisation`, then a smooth field (only when
    /// the field follows the curvature alone), then twice and half the strength, then the
    /// smooth field's quads laid out for level courses (only in level courses with quads
    /// raised to a course's pitch), then the smooth field free of the boundary (only where
    /// the first try follows an edge with corners and `boundary` is automatic). The tiles that
    /// fit best are kept (README, *Tries*).
    pub tries: u32,
}

/// The default run options.
#[unsafe(no_mangle)]
pub extern "C" fn tp_run_options_default() -> TpRunOptions {
    TpRunOptions {
        struct_size: size_of::<TpRunOptions>() as u32,
        tries: 0,
    }
}

/// Fills `*options`, a `TpRunOptions` of `size` bytes (pass `sizeof *options`), with the
/// defaults; it never writes more than `size` bytes.
///
/// # Safety
/// `options` must point to `size` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_run_options_init(options: *mut TpRunOptions, size: usize) -> TpStatus {
    // SAFETY: forwarded.
    guard(|| unsafe { init_options(options, size, tp_run_options_default(), "options") })
}

/// Tiles a triangle or polygon surface in one call, as the command line's `run`: quadrangulates
/// it (`remesh`), matches the quads (`pattern`) and places, fits and cuts the tiles (`tiles`),
/// on up to six quad meshes (`run->tries`), and keeps the tiles that fit best. Their report
/// (`tp_tiles_report_json`) lists every try (`tries`) and the one kept (`chosen_try`).
///
/// `*out_tiles` gets the kept tiles; `*out_quads` and `*out_pattern` (each may be NULL when
/// not wanted) the quad mesh and the pattern they were made from, read with the `tp_mesh_*`
/// and `tp_pattern_*` functions. Nothing is written to them on failure.
///
/// The pattern options' `zones` and `excluded_faces` are given per face of `surface`: each
/// quad takes the zone of the surface face closest to it, and is left out (neither tiled,
/// nor filled, nor counted in the coverage) when that face is excluded. Forced pairs name
/// quads, which do not exist before the call, so they are refused here (use the stages one
/// by one).
/// `progress` (may be NULL) is called with `TP_STAGE_RUN` and the share of the whole run done, each
/// try an equal share; a non-zero return cancels the run, in whichever try and stage, and the call
/// returns `TP_CANCELLED` without tiles. Each stage keeps its own time limit, except that a later
/// try's pattern stage has at most 10 s (the smooth field's try has the caller's where the first
/// try's quads end rows all over the surface); a later try whose pattern stage or fit reaches its
/// limit ends the tries, and so does the first try's fit, or its pattern stage when that limit is
/// 10 s or less (the report's `tries[].limit_reached` and `tries[].ended_tries`), so the progress
/// may end short of 1.
///
/// # Safety
/// `surface` must be a live mesh; the four options valid, their arrays holding their stated
/// counts; `out_tiles` writable, `out_quads` and `out_pattern` NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn tp_run(
    surface: *const TpMesh,
    remesh: *const TpRemeshOptions,
    pattern: *const TpPatternOptions,
    tiles: *const TpTileOptions,
    run: *const TpRunOptions,
    progress: TpProgressCallback,
    user: *mut c_void,
    out_quads: *mut *mut TpMesh,
    out_pattern: *mut *mut TpPattern,
    out_tiles: *mut *mut TpTiles,
) -> TpStatus {
    guard(|| {
        if out_tiles.is_null() {
            return Err(Failure::null("out_tiles"));
        }
        // SAFETY: a live handle and valid options by the caller's promise.
        let (surface, raw_remesh, raw_pattern, raw_tiles, raw_run) = unsafe {
            (
                &borrow(surface, "surface")?.mesh,
                read_options(remesh, tp_remesh_options_default(), "remesh")?,
                read_options(pattern, tp_pattern_options_default(), "pattern")?,
                read_options(tiles, tp_tile_options_default(), "tiles")?,
                read_options(run, tp_run_options_default(), "run")?,
            )
        };
        let tries = match raw_run.tries {
            0 => Tries::Auto,
            n if n as usize <= MAX_TRIES => Tries::Count(n as usize),
            n => {
                return Err(Failure::new(
                    TpStatus::TP_INVALID_ARGUMENT,
                    format!("run->tries is {n}: give 0 (automatic) or 1 to {MAX_TRIES}"),
                ));
            }
        };
        let count = raw_pattern.forced_pair_count;
        if count != 0 {
            return Err(Failure::new(
                TpStatus::TP_INVALID_ARGUMENT,
                format!(
                    "pattern->forced_pair_count is {count}: tp_run makes the quads itself, so no quad can be named before it; leave it 0, or run tp_remesh, tp_pattern_solve and tp_tiles_build_on_surface one by one (excluded faces, as zones, name faces of the surface and are taken)"
                ),
            ));
        }
        // SAFETY: the arrays hold their stated counts by the caller's promise.
        let remesh = unsafe { remesh_options(surface, &raw_remesh) }?;
        let options = pattern_options(&raw_pattern)?;
        let bond = options.bond;
        let mut report = progress_reporter(progress, user, TP_STAGE_RUN);
        // A cancel ends the run whichever stage hears it (every stage hears this callback): a
        // fit cancelled in a later try keeps its placement, is not kept and ends the tries,
        // which would then return an earlier try's tiles.
        let mut cancelled = false;
        let mut heard = |fraction: f64, _: Option<Figures>| {
            let going = report(fraction);
            cancelled |= !going;
            going
        };
        let found = pipeline::tile_surface_tries(
            surface,
            &remesh,
            &options,
            &raw_tiles.spec(),
            &raw_tiles.finish(bond),
            tries,
            &mut Control::with_figures(&mut heard),
        );
        if cancelled {
            return Err(Failure::new(
                TpStatus::TP_CANCELLED,
                "cancelled by the progress callback",
            ));
        }
        let (remeshed, tiling) = found?;
        // SAFETY: out_tiles checked non-null above; the others NULL (skipped) or writable by
        // the caller's promise.
        unsafe {
            if !out_quads.is_null() {
                hand_over(out_quads, TpMesh::made(remeshed.quads), "out_quads")?;
            }
            if !out_pattern.is_null() {
                let pattern = TpPattern {
                    pattern: tiling.pattern.clone(),
                    bond,
                };
                hand_over(out_pattern, pattern, "out_pattern")?;
            }
            hand_over(out_tiles, TpTiles { tiling }, "out_tiles")
        }
    })
}
