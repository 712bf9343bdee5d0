//! Stage 1 through the C ABI.

use std::ffi::c_void;

use super::status::{Failure, TpStatus, TpStatus::*, guard};
use super::{
    TP_STAGE_REMESH, TpMesh, TpProgressCallback, borrow, hand_over, init_options, input,
    progress_reporter, read_options,
};
use crate::control::Control;
use crate::remesh::{self, FieldDirection, GuideCurves, RemeshError, RemeshOptions, UserField};

/// `direction`: follow the principal curvature (the paper's choice).
pub const TP_DIRECTION_CURVATURE: i32 = 0;
/// `direction`: follow `direction_vector`, projected onto the surface.
pub const TP_DIRECTION_VECTOR: i32 = 1;
/// `direction`: the curvature field rotated by `angle_degrees`.
pub const TP_DIRECTION_ANGLE: i32 = 2;
/// `direction`: follow nothing, the boundary and smoothness alone orient the quads (the
/// second of `tp_run`'s tries): where the curvature lines converge (a cone, a funnel, a
/// bend) its quads end fewer rows and the tiles on them are cut less.
pub const TP_DIRECTION_SMOOTH: i32 = 3;

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
    /// `TP_TIME_LIMIT`. Callers compiled with an older, shorter struct get the default for
    /// this and every later field.
    pub time_limit_seconds: f64,
    /// The designer's direction field (e.g. principal stress or thrust directions): `3 *
    /// field_count` doubles, xyz per vector, one vector per mesh vertex or one per mesh face
    /// (told apart by `field_count`); NULL with `field_count` 0 (default) for none. Signs and
    /// lengths do not matter; every vector must be finite and non-zero. Read during
    /// `tp_remesh` only.
    pub field_vectors: *const f64,
    /// Number of vectors at `field_vectors`: the mesh's vertex or face count, or 0.
    pub field_count: usize,
    /// Share of the field against the curvature field (or `direction`), 0 to 1; default 1.
    pub field_weight: f64,
    /// Guide curves the quad rows follow near them (ABI 6): the points of every polyline one
    /// after the other, `3 * guide_point_count` doubles (xyz, model units); NULL with
    /// `guide_count` 0 (default) for none. Read during `tp_remesh` only.
    pub guide_points: *const f64,
    /// Number of points at `guide_points`: the sum of `guide_curve_sizes`.
    pub guide_point_count: usize,
    /// Points per polyline, `guide_count` numbers, each at least 2: curve `k` is the
    /// `guide_curve_sizes[k]` points after those of the curves before it.
    pub guide_curve_sizes: *const u32,
    /// Number of guide curves; 0 (default) for none.
    pub guide_count: usize,
    /// Share of the guides on the curves against every other source, 0 to 1 (falling off to
    /// nothing 2 target edges away); default 1.
    pub guide_weight: f64,
    /// Non-zero (default): each sheet between the creases that part the surface (a groin
    /// vault's webs) gets quads of its own, its field never aligned to the crease; zero runs
    /// one field over the whole surface. Pair it with `TpTileOptions.creases`. Since ABI 7.
    pub creases: i32,
    /// Strength of the field's renormalising steps, which place its cones and with them
    /// where rows end; any finite value from 0, default 0.5. Other strengths give other,
    /// equally valid quad meshes whose tiles may fit better: the command line's `run` tries
    /// 0.5, 1 and 0.25 and keeps the best tiles (README, *Tries*). Since ABI 8; older callers
    /// get the default.
    pub renormalisation: f64,
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
        field_vectors: std::ptr::null(),
        field_count: 0,
        field_weight: 1.0,
        guide_points: std::ptr::null(),
        guide_point_count: 0,
        guide_curve_sizes: std::ptr::null(),
        guide_count: 0,
        guide_weight: 1.0,
        creases: 1,
        renormalisation: remesh::RENORMALISATION,
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
        // SAFETY: the arrays hold their stated counts by the caller's promise.
        let options = unsafe { remesh_options(surface, &raw) }?;
        let mut report = progress_reporter(progress, user, TP_STAGE_REMESH);
        let remeshed =
            remesh::remesh_with(surface, &options, &mut Control::with_progress(&mut report))?;
        // SAFETY: checked non-null above.
        unsafe { hand_over(out, TpMesh::made(remeshed.quads), "out") }
    })
}

/// The library's remesh options from the C ones, every value checked (the field and guide
/// arrays read against `surface`).
///
/// # Safety
/// `raw`'s arrays must hold their stated counts (see [`read_field`], [`read_guides`]).
pub(super) unsafe fn remesh_options(
    surface: &crate::mesh::PolyMesh,
    raw: &TpRemeshOptions,
) -> Result<RemeshOptions, Failure> {
    let direction = match raw.direction {
        TP_DIRECTION_CURVATURE => FieldDirection::Curvature,
        TP_DIRECTION_VECTOR => FieldDirection::Vector(raw.direction_vector),
        TP_DIRECTION_ANGLE => FieldDirection::Angle(raw.angle_degrees),
        TP_DIRECTION_SMOOTH => FieldDirection::Smooth,
        other => {
            return Err(Failure::new(
                TP_INVALID_ARGUMENT,
                format!(
                    "direction {other} is not one of TP_DIRECTION_CURVATURE, TP_DIRECTION_VECTOR, TP_DIRECTION_ANGLE, TP_DIRECTION_SMOOTH"
                ),
            ));
        }
    };
    let time_limit = RemeshOptions::time_limit_from_secs(raw.time_limit_seconds)?;
    // SAFETY: the caller's promise on field_vectors.
    let user_field = unsafe { read_field(surface, raw) }?;
    // SAFETY: the caller's promise on guide_points and guide_curve_sizes.
    let guides = unsafe { read_guides(raw) }?;
    Ok(RemeshOptions {
        target_edge: raw.target_edge,
        direction,
        user_field,
        guides,
        shapeup: raw.shapeup != 0,
        creases: raw.creases != 0,
        time_limit,
        renormalisation: raw.renormalisation,
        ..RemeshOptions::default()
    })
}

/// The user field of `raw`, checked against `mesh` (the count before anything is read).
///
/// # Safety
/// `raw.field_vectors` must be NULL or point to `3 * raw.field_count` readable doubles.
unsafe fn read_field(
    mesh: &crate::mesh::PolyMesh,
    raw: &TpRemeshOptions,
) -> Result<Option<UserField>, Failure> {
    if raw.field_count == 0 {
        return Ok(None);
    }
    if raw.field_vectors.is_null() {
        return Err(Failure::null("options->field_vectors"));
    }
    if raw.field_count != mesh.positions().len() && raw.field_count != mesh.face_count() {
        return Err(RemeshError::FieldCount {
            given: raw.field_count,
            vertices: mesh.positions().len(),
            faces: mesh.face_count(),
        }
        .into());
    }
    // SAFETY: the count is the mesh's vertex or face count, and the caller promises that
    // many vectors.
    let flat = unsafe { std::slice::from_raw_parts(raw.field_vectors, 3 * raw.field_count) };
    let vectors = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let field = UserField::for_mesh(mesh, vectors, raw.field_weight)?;
    field.check(mesh)?;
    Ok(Some(field))
}

/// The guide curves of `raw`, checked on their own (the sizes against the point count before
/// any point is read).
///
/// # Safety
/// `raw.guide_curve_sizes` must be NULL or point to `raw.guide_count` readable `u32`s,
/// `raw.guide_points` NULL or to `3 * raw.guide_point_count` readable doubles.
unsafe fn read_guides(raw: &TpRemeshOptions) -> Result<Option<GuideCurves>, Failure> {
    if raw.guide_count == 0 {
        return Ok(None);
    }
    // SAFETY: the caller's promise on guide_curve_sizes.
    let sizes = unsafe {
        input(
            raw.guide_curve_sizes,
            raw.guide_count,
            "options->guide_curve_sizes",
        )
    }?;
    let total: u64 = sizes.iter().map(|&n| u64::from(n)).sum();
    if total != raw.guide_point_count as u64 {
        return Err(Failure::new(
            TP_INVALID_ARGUMENT,
            format!(
                "options->guide_curve_sizes add up to {total} points but guide_point_count is {}; give the points of every curve, one curve after the other",
                raw.guide_point_count
            ),
        ));
    }
    let flat = match raw.guide_point_count.checked_mul(3) {
        // SAFETY: the caller promises 3 * guide_point_count doubles.
        Some(n) => unsafe { input(raw.guide_points, n, "options->guide_points") }?,
        None => {
            return Err(Failure::new(
                TP_INVALID_ARGUMENT,
                "options->guide_point_count is too large",
            ));
        }
    };
    let mut points = flat.chunks_exact(3).map(|c| [c[0], c[1], c[2]]);
    let curves = sizes
        .iter()
        .map(|&n| points.by_ref().take(n as usize).collect())
        .collect();
    let guides = GuideCurves {
        curves,
        weight: raw.guide_weight,
    };
    guides.check()?;
    Ok(Some(guides))
}
