//! Status codes and the thread-local error message behind every export.

use std::cell::RefCell;
use std::ffi::{CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

use crate::mesh::MeshError;
use crate::pattern::PatternError;
use crate::pipeline::Error;
use crate::remesh::RemeshError;
use crate::tiles::TileError;

/// What a call did. The numbers are stable: new codes get new numbers, none is reused.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TpStatus {
    /// Success.
    TP_OK = 0,
    /// A required pointer was NULL.
    TP_NULL_POINTER = 1,
    /// An argument or option is out of range (a weight, a time limit, a tile size, a face
    /// index in the options, a `struct_size`).
    TP_INVALID_ARGUMENT = 2,
    /// The caller's buffer is smaller than the data; nothing was written.
    TP_BUFFER_TOO_SMALL = 3,
    /// The mesh was refused (NaN coordinates, bad indices, non-manifold edges, empty mesh).
    TP_INVALID_MESH = 4,
    /// The pattern does not fit the mesh (pairs of non-adjacent faces, faces used twice).
    TP_INVALID_PATTERN = 5,
    /// The MIP solver failed.
    TP_SOLVER_FAILED = 6,
    /// The stage hit its time limit before it had any usable result.
    TP_TIME_LIMIT = 7,
    /// The progress callback asked to stop.
    TP_CANCELLED = 8,
    /// The stage is not available in this build.
    TP_NOT_AVAILABLE = 9,
    /// A bug: the library panicked. The panic was caught; the process and the caller's data
    /// are intact, but the handle being built was discarded.
    TP_PANIC = 10,
}

/// A failed call: its status and message.
pub(super) struct Failure {
    pub status: TpStatus,
    pub message: String,
}

impl Failure {
    pub fn new(status: TpStatus, message: impl Into<String>) -> Self {
        Self {
            status,
            message: message.into(),
        }
    }

    pub fn null(name: &str) -> Self {
        Self::new(TpStatus::TP_NULL_POINTER, format!("{name} is NULL"))
    }
}

impl From<MeshError> for Failure {
    fn from(e: MeshError) -> Self {
        // Counts over the limits are bad arguments (nothing was read), the rest bad meshes.
        let status = if matches!(e, MeshError::TooLarge { .. }) {
            TpStatus::TP_INVALID_ARGUMENT
        } else {
            TpStatus::TP_INVALID_MESH
        };
        Self::new(status, e.to_string())
    }
}

impl From<PatternError> for Failure {
    fn from(e: PatternError) -> Self {
        let status = match e {
            PatternError::Cancelled => TpStatus::TP_CANCELLED,
            PatternError::Solver(_) => TpStatus::TP_SOLVER_FAILED,
            PatternError::InvalidWeight { .. }
            | PatternError::WeightTooLarge { .. }
            | PatternError::InvalidTimeLimit { .. }
            | PatternError::InvalidGap { .. }
            | PatternError::FaceOutOfRange { .. }
            | PatternError::ForcedNotAdjacent { .. }
            | PatternError::ForcedTwice { .. }
            | PatternError::ForcedExcluded { .. }
            | PatternError::ForcedNonQuad { .. }
            | PatternError::InvalidUp { .. }
            | PatternError::ForcedAcrossCourses { .. }
            | PatternError::BondAcrossCourses { .. }
            | PatternError::ZoneCount { .. }
            | PatternError::InvalidZone { .. } => TpStatus::TP_INVALID_ARGUMENT,
        };
        Self::new(status, e.to_string())
    }
}

impl From<TileError> for Failure {
    fn from(e: TileError) -> Self {
        let status = match e {
            TileError::InvalidSpec { .. }
            | TileError::NoUpDirection { .. }
            | TileError::OutOfProportion { .. }
            | TileError::TileLargerThanMesh { .. } => TpStatus::TP_INVALID_ARGUMENT,
            TileError::FaceOutOfRange { .. }
            | TileError::NotAdjacent { .. }
            | TileError::FaceUsedTwice { .. }
            | TileError::NotQuad { .. } => TpStatus::TP_INVALID_PATTERN,
        };
        Self::new(status, e.to_string())
    }
}

impl From<RemeshError> for Failure {
    fn from(e: RemeshError) -> Self {
        let status = match e {
            RemeshError::Mesh(_)
            | RemeshError::UnsupportedInput(_)
            | RemeshError::NothingExtracted(_) => TpStatus::TP_INVALID_MESH,
            RemeshError::Cancelled => TpStatus::TP_CANCELLED,
            RemeshError::TimeLimit { .. } => TpStatus::TP_TIME_LIMIT,
            _ => TpStatus::TP_INVALID_ARGUMENT,
        };
        Self::new(status, e.to_string())
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        match e {
            Error::Mesh(e) => e.into(),
            Error::Pattern(e) => e.into(),
            Error::Tiles(e) => e.into(),
            Error::Remesh(e) => e.into(),
            Error::TileTooSmall { .. } => Self::new(TpStatus::TP_INVALID_ARGUMENT, e.to_string()),
            Error::PatternMismatch { .. } => Self::new(TpStatus::TP_INVALID_PATTERN, e.to_string()),
        }
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Runs an export's body: records the message of a failure or a caught panic for
/// [`tp_last_error_message`] and returns the status.
pub(super) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> TpStatus {
    let outcome = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|panic| {
        let what = panic
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| panic.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        Err(Failure::new(
            TpStatus::TP_PANIC,
            format!("internal error (please report it): {what}"),
        ))
    });
    let (status, message) = match outcome {
        Ok(()) => (TpStatus::TP_OK, String::new()),
        Err(failure) => (failure.status, failure.message),
    };
    let message = CString::new(message.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|last| *last.borrow_mut() = message);
    status
}

/// Copies the message of this thread's last failed call (empty after a success) into `buf`
/// as a NUL-terminated string, truncated to `len - 1` bytes. Returns the message's full
/// length in bytes without the NUL, so `tp_last_error_message(NULL, 0)` asks for the size.
///
/// # Safety
/// `buf` is null or points to at least `len` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_last_error_message(buf: *mut c_char, len: usize) -> usize {
    catch_unwind(|| {
        LAST_ERROR.with(|last| {
            let bytes = last.borrow().as_bytes().to_vec();
            if !buf.is_null() && len > 0 {
                let n = bytes.len().min(len - 1);
                // SAFETY: the caller promises `buf` holds `len` bytes; we write n + 1 <= len.
                unsafe {
                    std::ptr::copy_nonoverlapping(bytes.as_ptr().cast::<c_char>(), buf, n);
                    *buf.add(n) = 0;
                }
            }
            bytes.len()
        })
    })
    .unwrap_or(0)
}
