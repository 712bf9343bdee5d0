//! The C ABI: our `extern "C"` exports (the outgoing solver bindings live in `solver`).
//!
//! Conventions, the same for every export:
//! - every function returns a [`TpStatus`] (except `tp_version`, `tp_abi_version`,
//!   `tp_last_error_message` and the `_free` functions); on failure
//!   [`tp_last_error_message`] tells why, naming the face or vertex at fault;
//! - no panic crosses the boundary: a caught panic becomes `TP_PANIC`;
//! - results live in opaque handles, released with their `_free` function (NULL is
//!   accepted); counts are read with `_count` functions and data is copied into the
//!   caller's buffers, which are checked against their stated capacity;
//! - options are `#[repr(C)]` structs whose first field `struct_size` is set by their
//!   `tp_*_options_default()`: a caller compiled against an older, shorter struct still
//!   works, the fields it does not know keep their defaults;
//! - long stages take an optional progress callback; a non-zero return cancels the stage,
//!   which then returns `TP_CANCELLED`. The callback runs on the calling thread.

#![allow(unsafe_code)]
#![allow(non_camel_case_types)]

mod mesh;
mod pattern;
mod remesh;
mod run;
mod status;
mod tiles;

pub use mesh::*;
pub use pattern::*;
pub use remesh::*;
pub use run::*;
pub use status::{TpStatus, tp_last_error_message};
pub use tiles::*;

use std::ffi::{c_char, c_void};

use status::{Failure, TpStatus::*};

/// Version of this ABI: raised when an existing function or struct changes incompatibly.
/// 2: `TpTileOptions` grew (boundary tiles); the `tp_*_options_init` functions were added so
/// that options structs can grow again without breaking callers built against older headers.
/// 3: `TpTileOptions` grew (the fit stage) and `TpPatternOptions` too (courses); callers
/// that initialise with `tp_*_options_init` keep working unchanged.
/// 4: `TpPatternOptions` grew (`gap`); callers built against ABI 3 keep working unchanged.
/// 5: `TpRemeshOptions` grew (the designer's field: `field_vectors`, `field_count`,
/// `field_weight`); callers built against ABI 4 keep working unchanged.
/// 6: `TpRemeshOptions` grew (guide curves: `guide_points`, `guide_point_count`,
/// `guide_curve_sizes`, `guide_count`, `guide_weight`) and `TpPatternOptions` grew (zones,
/// a bond per face: `zones`, `zone_count`); callers built against ABI 4 or 5 keep working
/// unchanged.
/// 7: `TpRemeshOptions` and `TpTileOptions` grew (`creases`: split the surface at its creases,
/// on by default); callers built against ABI 4 to 6 keep working unchanged (and get it on).
/// 8: `TpRemeshOptions` grew (`renormalisation`: the strength that places the field's cones,
/// default 0.5); callers built against ABI 4 to 7 keep working unchanged (and get 0.5).
/// 9: `tp_run` (the whole pipeline, with tries), `TpRunOptions` and `TP_STAGE_RUN` added;
/// nothing existing changed, callers built against ABI 4 to 8 keep working unchanged.
/// 10: `tp_mesh_new_welded` (a mesh welded, zipped and oriented as the command line reads a
/// file) and `tp_mesh_copy_sources` added, and `tp_run` takes excluded faces (per face of the
/// surface) where it refused them; callers built against ABI 4 to 9 keep working unchanged.
pub const TP_ABI_VERSION: u32 = 10;

/// Stage numbers passed to a progress callback.
pub const TP_STAGE_REMESH: u32 = 1;
/// The pattern (matching) stage.
pub const TP_STAGE_PATTERN: u32 = 2;
/// The tile stage (placing, the fit of joints, cutting).
pub const TP_STAGE_TILES: u32 = 3;
/// The whole pipeline of [`tp_run`]: every stage of every try (since ABI 9).
pub const TP_STAGE_RUN: u32 = 4;

/// A progress callback: `fraction` in `[0, 1]` of `stage` (a `TP_STAGE_*`) is done; return
/// non-zero to cancel. Called on the thread that called the stage.
pub type TpProgressCallback =
    Option<unsafe extern "C" fn(user: *mut c_void, stage: u32, fraction: f64) -> i32>;

/// The library version as a static NUL-terminated string, e.g. "0.1.0".
#[unsafe(no_mangle)]
pub extern "C" fn tp_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// [`TP_ABI_VERSION`] of the library actually loaded; compare it with the header's.
#[unsafe(no_mangle)]
pub extern "C" fn tp_abi_version() -> u32 {
    TP_ABI_VERSION
}

/// Panics on purpose, to prove that the boundary turns a panic into `TP_PANIC`.
#[cfg(feature = "test-panic")]
#[unsafe(no_mangle)]
pub extern "C" fn tp_test_panic() -> TpStatus {
    status::guard(|| panic!("tp_test_panic was called"))
}

/// The caller's array of `count` items at `ptr` (NULL allowed when `count` is 0).
///
/// # Safety
/// `ptr` must point to `count` valid items that stay untouched during the call.
unsafe fn input<'a, T>(ptr: *const T, count: usize, name: &str) -> Result<&'a [T], Failure> {
    if count == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(Failure::null(name));
    }
    if count
        .checked_mul(size_of::<T>())
        .is_none_or(|bytes| bytes > isize::MAX as usize)
    {
        return Err(Failure::new(
            TP_INVALID_ARGUMENT,
            format!("{name}: count {count} is too large"),
        ));
    }
    // SAFETY: non-null, size checked, validity promised by the caller.
    Ok(unsafe { std::slice::from_raw_parts(ptr, count) })
}

/// Copies `data` into the caller's buffer of `capacity` items.
///
/// # Safety
/// `out` must point to `capacity` writable items.
unsafe fn output<T: Copy>(
    data: &[T],
    out: *mut T,
    capacity: usize,
    name: &str,
) -> Result<(), Failure> {
    if data.is_empty() {
        return Ok(());
    }
    if capacity < data.len() {
        return Err(Failure::new(
            TP_BUFFER_TOO_SMALL,
            format!("{name} holds {capacity} items, {} are needed", data.len()),
        ));
    }
    if out.is_null() {
        return Err(Failure::null(name));
    }
    // SAFETY: the caller promises `capacity >= data.len()` writable items at `out`.
    unsafe { std::ptr::copy_nonoverlapping(data.as_ptr(), out, data.len()) };
    Ok(())
}

/// Writes one value through an out pointer.
///
/// # Safety
/// `out` must be NULL or point to a writable `T`.
unsafe fn write_out<T>(out: *mut T, value: T, name: &str) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null(name));
    }
    // SAFETY: non-null, writable by the caller's promise.
    unsafe { out.write(value) };
    Ok(())
}

/// Borrows the object behind a handle.
///
/// # Safety
/// `handle` must be NULL or a live handle of this type.
unsafe fn borrow<'a, T>(handle: *const T, name: &str) -> Result<&'a T, Failure> {
    // SAFETY: live handle by the caller's promise.
    unsafe { handle.as_ref() }.ok_or_else(|| Failure::null(name))
}

/// Reads a versioned options struct: the first `struct_size` bytes the caller knows about
/// over the current defaults.
///
/// # Safety
/// `options` must be NULL or point to at least `struct_size` readable bytes, where
/// `struct_size` is the struct's first field (a `u32`).
unsafe fn read_options<T: Copy>(options: *const T, defaults: T, name: &str) -> Result<T, Failure> {
    if options.is_null() {
        return Err(Failure::null(name));
    }
    // SAFETY: every options struct starts with its `u32` size.
    let size = unsafe { options.cast::<u32>().read_unaligned() } as usize;
    if size < size_of::<u32>() || size > 1 << 16 {
        return Err(Failure::new(
            TP_INVALID_ARGUMENT,
            format!(
                "{name}->struct_size is {size}: initialise options with their tp_*_options_default()"
            ),
        ));
    }
    let mut merged = defaults;
    let n = size.min(size_of::<T>());
    // SAFETY: the caller's struct has `size >= n` bytes; ours has `size_of::<T>() >= n`.
    unsafe {
        std::ptr::copy_nonoverlapping(options.cast::<u8>(), (&raw mut merged).cast::<u8>(), n)
    };
    Ok(merged)
}

/// Fills the caller's options struct of `size` bytes with `defaults`: the fields both sides
/// know get their default, `struct_size` becomes `size`, bytes of a newer caller's fields
/// this library does not know are zeroed. Unlike returning the struct by value, this never
/// writes past the caller's struct when the library's is larger.
///
/// # Safety
/// `out` must be NULL or point to `size` writable bytes.
unsafe fn init_options<T: Copy>(
    out: *mut T,
    size: usize,
    defaults: T,
    name: &str,
) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::null(name));
    }
    if size < size_of::<u32>() || size > 1 << 16 {
        return Err(Failure::new(
            TP_INVALID_ARGUMENT,
            format!(
                "{name}: size {size} is not the size of an options struct; pass sizeof(*{name})"
            ),
        ));
    }
    let known = size.min(size_of::<T>());
    let bytes = out.cast::<u8>();
    // SAFETY: the caller promises `size` writable bytes at `out`; `defaults` has
    // `size_of::<T>() >= known` bytes.
    unsafe {
        std::ptr::copy_nonoverlapping((&raw const defaults).cast::<u8>(), bytes, known);
        std::ptr::write_bytes(bytes.add(known), 0, size - known);
        bytes.cast::<u32>().write_unaligned(size as u32);
    }
    Ok(())
}

/// Moves a result into a new handle for the caller.
///
/// # Safety
/// `out` must be NULL or point to a writable handle pointer.
unsafe fn hand_over<T>(out: *mut *mut T, value: T, name: &str) -> Result<(), Failure> {
    // SAFETY: forwarded.
    unsafe { write_out(out, Box::into_raw(Box::new(value)), name) }
}

/// Releases a handle made by [`hand_over`].
///
/// # Safety
/// `handle` must be NULL or a live handle of this type, not used afterwards.
unsafe fn release<T>(handle: *mut T) {
    if !handle.is_null() {
        // SAFETY: made by Box::into_raw in `hand_over`, released once by the caller's promise.
        drop(unsafe { Box::from_raw(handle) });
    }
}

/// Calls the caller's progress callback for `stage`; `false` means cancel.
fn progress_reporter(
    callback: TpProgressCallback,
    user: *mut c_void,
    stage: u32,
) -> impl FnMut(f64) -> bool {
    move |fraction| match callback {
        // SAFETY: the caller gave this callback and user pointer for the duration of the call.
        Some(f) => (unsafe { f(user, stage, fraction) }) == 0,
        None => true,
    }
}

/// Copies `text` NUL-terminated into the caller's buffer of `len` bytes and writes its length
/// without the NUL to `needed` (if not NULL). A short buffer gets nothing and
/// `TP_BUFFER_TOO_SMALL`, so callers can ask with `len = 0` first.
///
/// # Safety
/// `buf` must hold `len` bytes; `needed` must be NULL or writable.
unsafe fn output_text(
    text: &str,
    buf: *mut c_char,
    len: usize,
    needed: *mut usize,
) -> Result<(), Failure> {
    if !needed.is_null() {
        // SAFETY: non-null and writable by the caller's promise.
        unsafe { write_out(needed, text.len(), "needed") }?;
    }
    let mut bytes = text.as_bytes().to_vec();
    bytes.push(0);
    // SAFETY: capacity as promised.
    unsafe { output(&bytes, buf.cast::<u8>(), len, "buf") }
}
