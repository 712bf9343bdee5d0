//! Stage 1 through the C ABI.

use std::ffi::c_void;

use super::status::{Failure, TpStatus, TpStatus::*, guard};
use super::{
    TP_STAGE_REMESH, TpMesh, TpProgressCallback, borrow, hand_over, init_options,
    progress_reporter, read_options,
};
use crate::control::Control;
use crate::remesh::{self, FieldDirection, RemeshError, RemeshOptions};

/// `direction`: follow the principal curvature (the paper's choice).
pub const TP_DIRECTION_CURVATURE: i32 = 0;
/// `direction`: follow `direction_vector`, projected onto the surface.
pub const TP_DIRECTION_VECTOR: i32 = 1;
/// `direction`: the curvature field rotated by `angle_degrees`.
pub const TP_DIRECTION_ANGLE: i32 = 2;

/// Options of [`tp_remesh`]. Initialise with [`tp_remesh_options_default`].
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpRemeshOptions {
    /// `sizeof(TpRemeshOptions)` as compiled by the caller; set by the default initialiser.
    pub struct_size: u32,
    /// Target quad edge in model units; default 0.145 ((280 + 10) / 2 mm in metres).
    pub target_edge: f64,
    /// `TP_DIRECTION_*`; default curvature.
    pub direction: i32,
    /// The direction for `TP_DIRECTION_VECTOR`, as xyz.
    pub direction_vector: [f64; 3],
    /// The rotation for `TP_DIRECTION_ANGLE`, in degrees.
    pub angle_degrees: f64,
    /// Non-zero: pull faces towards squares (shape-up) without leaving the surface.
    pub shapeup: i32,
    /// Wall-clock limit of the stage in seconds; default 60. When it passes, the quad mesh as
    /// it stands is returned if one exists (the final fitting is cut short), otherwise
    /// `TP_TIME_LIMIT`. The last field: callers compiled with an older, shorter struct get
    /// the default.
    pub time_limit_seconds: f64,
}

/// The default remesh options.
#[unsafe(no_mangle)]
pub extern "C" fn tp_remesh_options_default() -> TpRemeshOptions {
    TpRemeshOptions {
        struct_size: size_of::<TpRemeshOptions>() as u32,
        target_edge: 0.145,
        direction: TP_DIRECTION_CURVATURE,
        direction_vector: [1.0, 0.0, 0.0],
        angle_degrees: 0.0,
        shapeup: 0,
        time_limit_seconds: 60.0,
    }
}

/// Fills `*options`, a `TpRemeshOptions` of `size` bytes (pass `sizeof *options`), with the
/// defaults. Prefer this to [`tp_remesh_options_default`] in code that may load a newer library: it
/// never writes more than `size` bytes.
///
/// # Safety
/// `options` must point to `size` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_remesh_options_init(
    options: *mut TpRemeshOptions,
    size: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    guard(|| unsafe { init_options(options, size, tp_remesh_options_default(), "options") })
}

/// Quadrangulates `mesh` (a triangle or polygon surface) into near-square quads (stage 1);
/// `*out` gets the quad mesh, read it with the `tp_mesh_*` functions. `progress` (may be NULL)
/// is told the fraction done during the stage (from 0 to 1, about every 10 ms); a non-zero
/// return cancels it, and `tp_remesh` returns `TP_CANCELLED` soon after. `TP_TIME_LIMIT` when
/// `time_limit_seconds` passed before any quad mesh was ready.
///
/// # Safety
/// `mesh` must be a live mesh, `options` valid, `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_remesh(
    mesh: *const TpMesh,
    options: *const TpRemeshOptions,
    progress: TpProgressCallback,
    user: *mut c_void,
    out: *mut *mut TpMesh,
) -> TpStatus {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        // SAFETY: live handle and valid options by the caller's promise.
        let (surface, raw) = unsafe {
            (
                &borrow(mesh, "mesh")?.mesh,
                read_options(options, tp_remesh_options_default(), "options")?,
            )
        };
        let direction = match raw.direction {
            TP_DIRECTION_CURVATURE => FieldDirection::Curvature,
            TP_DIRECTION_VECTOR => FieldDirection::Vector(raw.direction_vector),
            TP_DIRECTION_ANGLE => FieldDirection::Angle(raw.angle_degrees),
            other => {
                return Err(Failure::new(
                    TP_INVALID_ARGUMENT,
                    format!(
                        "direction {other} is not one of TP_DIRECTION_CURVATURE, TP_DIRECTION_VECTOR, TP_DIRECTION_ANGLE"
                    ),
                ));
            }
        };
        let time_limit = RemeshOptions::time_limit_from_secs(raw.time_limit_seconds)?;
        let options = RemeshOptions {
            target_edge: raw.target_edge,
            direction,
            shapeup: raw.shapeup != 0,
            time_limit,
            ..RemeshOptions::default()
        };
        let mut report = progress_reporter(progress, user, TP_STAGE_REMESH);
        let remeshed =
            remesh::remesh_with(surface, &options, &mut Control::with_progress(&mut report))
                .map_err(|e| match e {
                    RemeshError::Cancelled => Failure::new(TP_CANCELLED, e.to_string()),
                    RemeshError::TimeLimit { .. } => Failure::new(TP_TIME_LIMIT, e.to_string()),
                    other => other.into(),
                })?;
        // SAFETY: checked non-null above.
        unsafe {
            hand_over(
                out,
                TpMesh {
                    mesh: remeshed.quads,
                },
                "out",
            )
        }
    })
}
