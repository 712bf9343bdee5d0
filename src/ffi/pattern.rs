//! Stage 2 through the C ABI: options, the solve, and the pattern's accessors.

use std::ffi::c_void;

use super::status::{Failure, TpStatus, TpStatus::*, guard};
use super::{
    TP_STAGE_PATTERN, TpMesh, TpProgressCallback, borrow, hand_over, init_options, input, output,
    progress_reporter, read_options, release, write_out,
};
use crate::control::Control;
use crate::pattern::{
    self, Bond, BoundSource, Courses, Formulation, Method, Pattern, PatternOptions, SolveStatus,
};

/// `bond`: maximum matching, the paper's eq. (1).
pub const TP_BOND_STACK: i32 = 0;
/// `bond`: staggered, eq. (2); `weight` is the penalty per continuous joint.
pub const TP_BOND_STAGGERED: i32 = 1;
/// `bond`: running bond, eq. (3); `weight` is the reward per shifted pair.
pub const TP_BOND_RUNNING: i32 = 2;
/// `bond`: herringbone (the 90-degree zig-zag); `weight` is the penalty per continuous joint
/// and per pair laid end to end. Needs `courses` free.
pub const TP_BOND_HERRINGBONE: i32 = 3;
/// `bond`: basket weave (2 x 2 squares of parallel tiles, alternating); `weight` is the
/// penalty per shifted, end-to-end and one-course-apart pair. Needs `courses` free.
pub const TP_BOND_BASKET_WEAVE: i32 = 4;
/// A zone (`TpPatternOptions::zones`) laid in the options' `bond`.
pub const TP_ZONE_DEFAULT: i32 = -1;
/// `method`: the fastest route to a proven optimum.
pub const TP_METHOD_AUTO: i32 = 0;
/// `method`: the paper's whole program on CBC.
pub const TP_METHOD_MIP: i32 = 1;
/// `formulation`: the paper's program plus valid rows (same optimum, faster proofs).
pub const TP_FORMULATION_STRENGTHENED: i32 = 0;
/// `formulation`: the program exactly as printed in the paper.
pub const TP_FORMULATION_PAPER: i32 = 1;
/// Summary `status`: the objective equals the proven bound.
pub const TP_SOLVE_OPTIMAL: i32 = 0;
/// Summary `status`: the time limit stopped the search; the pattern is valid, a gap remains.
pub const TP_SOLVE_TIME_LIMIT: i32 = 1;
/// Summary `status`: the search ended with a valid pattern and a gap.
pub const TP_SOLVE_FEASIBLE: i32 = 2;

/// [`tp_pattern_bound_source`]: a maximum matching bounds the number of tiles.
pub const TP_BOUND_MATCHING: i32 = 0;
/// [`tp_pattern_bound_source`]: the patch relaxations of a decomposition of the faces.
pub const TP_BOUND_PATCHES: i32 = 1;
/// [`tp_pattern_bound_source`]: branch and bound on the whole program.
pub const TP_BOUND_WHOLE_PROGRAM: i32 = 2;
/// [`tp_pattern_bound_source`]: the linear relaxation of the whole program, from its row
/// prices.
pub const TP_BOUND_LINEAR_RELAXATION: i32 = 3;

/// Options of [`tp_pattern_solve`]. Initialise with [`tp_pattern_options_default`].
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct TpPatternOptions {
    /// `sizeof(TpPatternOptions)` as compiled by the caller; set by the default initialiser.
    pub struct_size: u32,
    /// `TP_BOND_*`; default staggered.
    pub bond: i32,
    /// Weight of the bond term (w or w_R), from 0 to 1000; default 0.5.
    pub weight: f64,
    /// Wall-clock limit in seconds; default 60. Zero returns the greedy start; NaN, negative
    /// and infinite limits are refused, finite ones above 1e9 s count as 1e9 s.
    pub time_limit_seconds: f64,
    /// `TP_METHOD_*`; default auto.
    pub method: i32,
    /// `TP_FORMULATION_*`; default strengthened.
    pub formulation: i32,
    /// `forced_pair_count` pairs of face indices (2 per pair) that must become tiles.
    pub forced_pairs: *const u32,
    /// Number of forced pairs.
    pub forced_pair_count: usize,
    /// `excluded_face_count` faces that take part in no tile.
    pub excluded_faces: *const u32,
    /// Number of excluded faces.
    pub excluded_face_count: usize,
    /// `TP_COURSES_*`: tiles either way (`TP_COURSES_FREE`, default, the paper's model) or
    /// all along level courses (`TP_COURSES_LEVEL`), which fit far better where the tile's
    /// length plus a joint is not twice its width plus a joint. Since ABI 3.
    pub courses: i32,
    /// Up direction for level courses, xyz; default (0, 0, 1). Since ABI 3.
    pub up: [f64; 3],
    /// Relative gap at which the search stops, like a MIP solver's: once (bound - objective)
    /// / bound is at most this; from 0 (default: prove optimality or reach the time limit)
    /// to 1. A solve stopped by the gap has status `TP_SOLVE_FEASIBLE` (`TP_SOLVE_OPTIMAL`
    /// when proven). Since ABI 4.
    pub gap: f64,
    /// Zones: `zone_count` bonds, one per face of the mesh in face order, each a `TP_BOND_*`
    /// or -1 for `bond`; every zone at `weight` (e.g. a band of `TP_BOND_HERRINGBONE` in a
    /// staggered vault). A herringbone or basket-weave zone needs `courses` free. NULL by
    /// default. Since ABI 6.
    pub zones: *const i32,
    /// Number of zones: 0 (default) lays every face in `bond`; otherwise the mesh's face
    /// count. Since ABI 6.
    pub zone_count: usize,
}

/// Tiles may lie either way across any quad (the paper's eqs. 1-3).
pub const TP_COURSES_FREE: i32 = 0;
/// Tiles lie along level courses (see `Courses::Level`).
pub const TP_COURSES_LEVEL: i32 = 1;

/// Numbers describing a solved pattern.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct TpPatternSummary {
    /// Faces of the mesh.
    pub faces: usize,
    /// Matched pairs (full tiles).
    pub pairs: usize,
    /// Unpaired quads (half tiles).
    pub unpaired: usize,
    /// Excluded faces.
    pub excluded: usize,
    /// Faces that are not quads.
    pub non_quad: usize,
    /// Continuous joints in the pattern.
    pub continuous_joints: usize,
    /// Shifted pairs in the pattern.
    pub shifted_pairs: usize,
    /// Objective of the pattern.
    pub objective: f64,
    /// Proven upper bound on the objective.
    pub bound: f64,
    /// Relative gap between bound and objective.
    pub gap: f64,
    /// Wall-clock seconds of the solve.
    pub seconds: f64,
    /// `TP_SOLVE_*`.
    pub status: i32,
}

/// A solved pattern (opaque).
pub struct TpPattern {
    pub(super) pattern: Pattern,
    /// The bond it was solved for (the fit stage keeps it).
    pub(super) bond: Bond,
}

/// The default pattern options.
#[unsafe(no_mangle)]
pub extern "C" fn tp_pattern_options_default() -> TpPatternOptions {
    TpPatternOptions {
        struct_size: size_of::<TpPatternOptions>() as u32,
        bond: TP_BOND_STAGGERED,
        weight: pattern::DEFAULT_WEIGHT,
        time_limit_seconds: 60.0,
        method: TP_METHOD_AUTO,
        formulation: TP_FORMULATION_STRENGTHENED,
        forced_pairs: std::ptr::null(),
        forced_pair_count: 0,
        excluded_faces: std::ptr::null(),
        excluded_face_count: 0,
        courses: TP_COURSES_FREE,
        up: [0.0, 0.0, 1.0],
        gap: 0.0,
        zones: std::ptr::null(),
        zone_count: 0,
    }
}

/// Fills `*options`, a `TpPatternOptions` of `size` bytes (pass `sizeof *options`), with the
/// defaults. Prefer this to [`tp_pattern_options_default`] in code that may load a newer library: it
/// never writes more than `size` bytes.
///
/// # Safety
/// `options` must point to `size` writable bytes.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_options_init(
    options: *mut TpPatternOptions,
    size: usize,
) -> TpStatus {
    // SAFETY: forwarded.
    guard(|| unsafe { init_options(options, size, tp_pattern_options_default(), "options") })
}

/// Matches the faces of `mesh` into tiles. `progress` (may be NULL) is called with
/// `TP_STAGE_PATTERN` and the share of the time limit used; a non-zero return cancels the
/// solve (CBC and Clp too, at their next node or iteration) within a fraction of a second
/// and returns `TP_CANCELLED`, leaving nothing running. A solve stopped by the time
/// limit still succeeds: read its status with [`tp_pattern_summary`].
///
/// # Safety
/// `mesh` must be a live mesh, `options` a valid options struct whose arrays hold their
/// stated counts, `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_solve(
    mesh: *const TpMesh,
    options: *const TpPatternOptions,
    progress: TpProgressCallback,
    user: *mut c_void,
    out: *mut *mut TpPattern,
) -> TpStatus {
    guard(|| {
        if out.is_null() {
            return Err(Failure::null("out"));
        }
        // SAFETY: live handle and valid options by the caller's promise.
        let (mesh, raw) = unsafe {
            (
                &borrow(mesh, "mesh")?.mesh,
                read_options(options, tp_pattern_options_default(), "options")?,
            )
        };
        let options = pattern_options(&raw)?;
        let mut report = progress_reporter(progress, user, TP_STAGE_PATTERN);
        let pattern =
            pattern::solve_with(mesh, &options, &mut Control::with_progress(&mut report))?;
        // SAFETY: checked non-null above.
        unsafe {
            hand_over(
                out,
                TpPattern {
                    pattern,
                    bond: options.bond,
                },
                "out",
            )
        }
    })
}

/// Converts C options into the library's, checking every value.
pub(super) fn pattern_options(raw: &TpPatternOptions) -> Result<PatternOptions, Failure> {
    let invalid = |what: String| Failure::new(TP_INVALID_ARGUMENT, what);
    let bond = bond_of(raw.bond, raw.weight)
        .ok_or_else(|| invalid(format!("bond {} is not one of {BOND_NAMES}", raw.bond)))?;
    let method = match raw.method {
        TP_METHOD_AUTO => Method::Auto,
        TP_METHOD_MIP => Method::Mip,
        other => {
            return Err(invalid(format!(
                "method {other} is not one of TP_METHOD_AUTO, TP_METHOD_MIP"
            )));
        }
    };
    let formulation = match raw.formulation {
        TP_FORMULATION_STRENGTHENED => Formulation::Strengthened,
        TP_FORMULATION_PAPER => Formulation::Paper,
        other => {
            return Err(invalid(format!(
                "formulation {other} is not one of TP_FORMULATION_STRENGTHENED, TP_FORMULATION_PAPER"
            )));
        }
    };
    // Refuse absurd counts before reading or copying the arrays: no mesh has more faces.
    for (name, count) in [
        ("forced_pair_count", raw.forced_pair_count),
        ("excluded_face_count", raw.excluded_face_count),
        ("zone_count", raw.zone_count),
    ] {
        if count > crate::mesh::MAX_FACES {
            return Err(invalid(format!(
                "options->{name} is {count}; a mesh has at most {} faces",
                crate::mesh::MAX_FACES
            )));
        }
    }
    let pair_values = 2 * raw.forced_pair_count;
    // SAFETY: the arrays hold their stated counts by the caller's promise.
    let (forced, excluded, zone_codes) = unsafe {
        (
            input(raw.forced_pairs, pair_values, "options->forced_pairs")?,
            input(
                raw.excluded_faces,
                raw.excluded_face_count,
                "options->excluded_faces",
            )?,
            input(raw.zones, raw.zone_count, "options->zones")?,
        )
    };
    // No zones (count 0) lays every face in `bond`; the count is checked against the mesh
    // by the pattern stage.
    let zones = (!zone_codes.is_empty())
        .then(|| {
            zone_codes
                .iter()
                .enumerate()
                .map(|(face, &code)| match code {
                    TP_ZONE_DEFAULT => Ok(bond),
                    _ => bond_of(code, raw.weight).ok_or_else(|| {
                        invalid(format!(
                            "options->zones[{face}] is {code}: give one of {BOND_NAMES}, or -1 for options->bond"
                        ))
                    }),
                })
                .collect::<Result<Vec<Bond>, Failure>>()
        })
        .transpose()?;
    Ok(PatternOptions {
        bond,
        time_limit: PatternOptions::time_limit_from_secs(raw.time_limit_seconds)?,
        forced_pairs: forced
            .chunks_exact(2)
            .map(|p| [p[0] as usize, p[1] as usize])
            .collect(),
        excluded_faces: excluded.iter().map(|&f| f as usize).collect(),
        formulation,
        method,
        courses: match raw.courses {
            TP_COURSES_FREE => Courses::Free,
            TP_COURSES_LEVEL => Courses::Level { up: raw.up },
            other => {
                return Err(invalid(format!(
                    "courses {other} is not one of TP_COURSES_FREE, TP_COURSES_LEVEL"
                )));
            }
        },
        gap: raw.gap,
        zones,
    })
}

/// The `TP_BOND_*` names, for messages.
const BOND_NAMES: &str =
    "TP_BOND_STACK, TP_BOND_STAGGERED, TP_BOND_RUNNING, TP_BOND_HERRINGBONE, TP_BOND_BASKET_WEAVE";

/// The bond of a `TP_BOND_*` code with `weight`, `None` for an unknown code.
fn bond_of(code: i32, weight: f64) -> Option<Bond> {
    Some(match code {
        TP_BOND_STACK => Bond::Stack,
        TP_BOND_STAGGERED => Bond::Staggered { weight },
        TP_BOND_RUNNING => Bond::RunningBond { weight },
        TP_BOND_HERRINGBONE => Bond::Herringbone { weight },
        TP_BOND_BASKET_WEAVE => Bond::BasketWeave { weight },
        _ => return None,
    })
}

/// Releases a pattern. NULL is accepted.
///
/// # Safety
/// `pattern` must be NULL or a live pattern, not used afterwards.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_free(pattern: *mut TpPattern) {
    // SAFETY: forwarded.
    unsafe { release(pattern) }
}

/// Writes the pattern's numbers into `*out`.
///
/// # Safety
/// `pattern` must be a live pattern and `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_summary(
    pattern: *const TpPattern,
    out: *mut TpPatternSummary,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        // The pattern's own summary (the report embeds the same), laid out for C.
        let p = unsafe { borrow(pattern, "pattern") }?.pattern.summary();
        let status = match p.status {
            SolveStatus::Optimal => TP_SOLVE_OPTIMAL,
            SolveStatus::TimeLimit => TP_SOLVE_TIME_LIMIT,
            SolveStatus::Feasible => TP_SOLVE_FEASIBLE,
        };
        let summary = TpPatternSummary {
            faces: p.faces,
            pairs: p.pairs,
            unpaired: p.unpaired,
            excluded: p.excluded,
            non_quad: p.non_quad,
            continuous_joints: p.continuous_joints,
            shifted_pairs: p.shifted_pairs,
            objective: p.objective,
            bound: p.bound,
            gap: p.gap,
            seconds: p.seconds,
            status,
        };
        // SAFETY: writable by the caller's promise.
        unsafe { write_out(out, summary, "out") }
    })
}

/// Writes into `*out` which argument proved the pattern's bound (`TP_BOUND_*`): with
/// `TP_SOLVE_OPTIMAL`, the one that closed the gap.
///
/// # Safety
/// `pattern` must be a live pattern and `out` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_bound_source(
    pattern: *const TpPattern,
    out: *mut i32,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let p = &unsafe { borrow(pattern, "pattern") }?.pattern;
        let source = match p.bound_source {
            BoundSource::Matching => TP_BOUND_MATCHING,
            BoundSource::Patches => TP_BOUND_PATCHES,
            BoundSource::WholeProgram => TP_BOUND_WHOLE_PROGRAM,
            BoundSource::LinearRelaxation => TP_BOUND_LINEAR_RELAXATION,
        };
        // SAFETY: writable by the caller's promise.
        unsafe { write_out(out, source, "out") }
    })
}

/// Copies the matched pairs as face-index pairs into `out` (capacity in `uint32_t`: 2 per
/// pair; the number of pairs is in the summary).
///
/// # Safety
/// `pattern` must be a live pattern and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_copy_pairs(
    pattern: *const TpPattern,
    out: *mut u32,
    capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let p = &unsafe { borrow(pattern, "pattern") }?.pattern;
        let flat: Vec<u32> = p.pairs.iter().flatten().map(|&f| f as u32).collect();
        // SAFETY: capacity as promised.
        unsafe { output(&flat, out, capacity, "out") }
    })
}

/// Copies the unpaired quads (future half tiles) into `out` (capacity: the summary's
/// `unpaired`).
///
/// # Safety
/// `pattern` must be a live pattern and `out` hold `capacity` items.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn tp_pattern_copy_unpaired(
    pattern: *const TpPattern,
    out: *mut u32,
    capacity: usize,
) -> TpStatus {
    guard(|| {
        // SAFETY: live handle by the caller's promise.
        let p = &unsafe { borrow(pattern, "pattern") }?.pattern;
        let faces: Vec<u32> = p.unpaired.iter().map(|&f| f as u32).collect();
        // SAFETY: capacity as promised.
        unsafe { output(&faces, out, capacity, "out") }
    })
}
