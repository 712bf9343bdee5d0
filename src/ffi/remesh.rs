//! Stage 1 through the C ABI. The remesher is not in this build yet: the entry point exists
//! so callers can be written against it, and it says so instead of returning a fake mesh.

use std::ffi::c_void;

use super::status::{Failure, TpStatus, TpStatus::*, guard};
use super::{TpMesh, TpProgressCallback, read_options};

/// Options of [`tp_remesh`]. Initialise with [`tp_remesh_options_default`].
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpRemeshOptions {
    /// `sizeof(TpRemeshOptions)` as compiled by the caller; set by the default initialiser.
    pub struct_size: u32,
    /// Target quad edge in model units; default 0.145 ((280 + 10) / 2 mm in metres).
    pub target_edge: f64,
}

/// The default remesh options.
#[unsafe(no_mangle)]
pub extern "C" fn tp_remesh_options_default() -> TpRemeshOptions {
    TpRemeshOptions { struct_size: size_of::<TpRemeshOptions>() as u32, target_edge: 0.145 }
}

/// Quadrangulates `mesh` into near-square quads (stage 1). Not available in this build:
/// returns `TP_NOT_AVAILABLE` after checking its arguments.
///
/// # Safety
/// `mesh` must be a live mesh, `options` valid, `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_remesh(
    mesh: *const TpMesh,
    options: *const TpRemeshOptions,
    _progress: TpProgressCallback,
    _user: *mut c_void,
    out: *mut *mut TpMesh,
) -> TpStatus {
    guard(|| {
        if mesh.is_null() || out.is_null() {
            return Err(Failure::null(if mesh.is_null() { "mesh" } else { "out" }));
        }
        // SAFETY: valid options by the caller's promise.
        unsafe { read_options(options, tp_remesh_options_default(), "options") }?;
        Err(Failure::new(TP_NOT_AVAILABLE, "the quad remesher (stage 1) is not in this build yet; pass a quad mesh to tp_pattern_solve"))
    })
}
