//! Stage 1 (paper section 3.1): turn a free-form triangle (or polygon) surface into a pure
//! quad mesh whose faces are near-squares of edge `t` (half a tile plus joint).
//!
//! The route is the field-guided one the paper describes, after Instant Meshes (Jakob,
//! Tarini, Panozzo, Sorkine-Hornung, "Instant field-aligned meshes", SIGGRAPH Asia 2015) and
//! QuadriFlow (Huang, Zhou, Niessner, Guibas, "QuadriFlow: a scalable and robust method for
//! quadrangulation", SGP 2018). Every step works on the [`surface`]: the triangulated input
//! with its adjacency, its boundary loops (corners, narrow parts) and a closest-point
//! locator on it.
//!
//! 1. [`field`]: a 4-RoSy orientation field, the globally smoothest one (Knöppel et al. 2013
//!    style complex representation, solved by conjugate gradients) that follows principal
//!    curvature where the surface is anisotropic, and is pinned to the boundary tangents so
//!    quads line up with the shell's edges, except where the boundary is narrower than a
//!    quad (teeth, slivers) or turns into an acute tongue;
//! 2. [`position`]: an isotropic lattice (position) field of spacing `t`, solved globally by
//!    least squares (cotangent-weighted, so skewed triangulations do not shear it) with
//!    integer lattice jumps that are re-rounded between solves (the Instant Meshes energy,
//!    with QuadriFlow's idea of fixing integer offsets globally), with boundary lattice
//!    lines pinned onto the boundary; the working surface is refined until no edge is longer
//!    than three quarters of a quad ([`refine`]);
//! 3. [`extract`]: vertices sharing a lattice point are collapsed, unit lattice offsets become
//!    quad edges, faces are traced in the tangent plane;
//! 4. [`cleanup`]: holes are filled, non-quads paired and split, doublets merged, so that the
//!    result is a pure, manifold quad mesh; then [`fit`]: where the quads stop short of the
//!    input boundary the boundary row is extended onto it, boundary vertices go onto the
//!    input boundary and every vertex onto the surface, faces that still leave the surface
//!    are pulled back, peeled and re-extended, or halved along their quad strip. Both keep
//!    the same [`anchors`] (boundary vertices on the boundary, corners on corners) and work
//!    on the face list through [`quadmesh`];
//! 5. [`shapeup`] (optional): local-global iterations towards squares of side `t`
//!    (Bouaziz et al., "Shape-Up", SGP 2012, as used in the paper via libigl), projected back
//!    onto the input after every step;
//! 6. [`metrics`](mod@metrics): the acceptance numbers, usable on any quad mesh.
//!
//! [`remesh_with`] reports progress and honours cancellation and a time limit ([`budget`]).
//!
//! Everything is deterministic: iteration is in index order, no hash-map order reaches a
//! result and no threads are used.

mod anchors;
mod budget;
mod cleanup;
mod extract;
mod field;
mod fit;
mod flow;
mod guides;
mod linalg;
mod metrics;
mod multigrid;
mod position;
mod quadmesh;
mod refine;
mod scale;
mod shapeup;
mod surface;
mod user_field;

use std::time::{Duration, Instant};

use budget::Budget;

use thiserror::Error;

use crate::control::Control;
use crate::mesh::{MeshError, PolyMesh, crease};

pub use guides::GuideCurves;
pub use metrics::{Metrics, edges_within_20pct, metrics};
pub use user_field::{FieldSite, UserField};

/// How the quads are oriented on the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FieldDirection {
    /// Follow the principal curvature directions where the surface is anisotropic (hypar,
    /// barrel vaults) and stay smooth elsewhere: the paper's choice, quads then bend least.
    Curvature,
    /// Follow a user direction (for example the span of a vault), projected into each tangent
    /// plane; where it is nearly normal to the surface the field just stays smooth.
    Vector([f64; 3]),
    /// The curvature directions rotated by an angle in degrees (45 gives a diagonal pattern).
    Angle(f64),
    /// Follow nothing: the boundary (where its loops are aligned) and smoothness alone orient
    /// the quads, as on a sphere. Where the curvature lines converge (a cone's rulings, the
    /// rings and meridians of a shell of revolution) square quads along them must end rows
    /// all over; the smoothest field spreads the turning instead, and rigid tiles fit it
    /// better there.
    Smooth,
}

/// Whether quad rows follow the boundary.
///
/// A cross field aligned to a closed boundary loop turns once around it; where the loop has
/// corners (a rectangular vault, a hypar) the corners absorb that turning, but a smooth loop
/// (a dome's circular rim, a round opening) forces four +1/4 (or -1/4) cones into the
/// interior and, with them, rings of rows that must lose quads towards the centre (Bommes et
/// al., "Mixed-integer quadrangulation", 2009, on the index theorem with boundaries).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoundaryAlignment {
    /// Align boundary loops that have corners (turning by more than 50 degrees); leave smooth
    /// loops free, their boundary quads are then trimmed to the loop.
    Auto,
    /// Align every boundary loop (quad rings along a dome's rim, at the price of cones).
    Always,
    /// Align no loop: the field follows curvature and smoothness only.
    Never,
}

/// Refuses a surface that falls apart into pieces of a face or two, more than [`CRUMBS`] of
/// them and more than a quarter of its faces, none of them holding half its area: an
/// unwelded triangle soup (read with `--weld off`, or given as arrays), on which no quad can
/// be laid, whose extraction found none and blamed the target edge. A few small pieces (two
/// quads touching at a corner) are left to the checks that name them, and so is debris
/// around a shell that holds most of the area (thousands of stray triangles a scan or an
/// export leaves: the shell is remeshed, the debris gets no quad, and the several-pieces
/// warning says so).
fn refuse_crumbs(input: &PolyMesh) -> Result<(), RemeshError> {
    let Ok(topology) = crate::mesh::Topology::new(input) else {
        return Ok(());
    };
    let pieces = topology.piece_areas(input);
    let count = pieces.areas.len();
    if count > CRUMBS && 4 * count > input.face_count() && pieces.main_share() < 0.5 {
        return Err(RemeshError::UnsupportedInput(format!(
            "the surface falls apart into {count} pieces of {} faces, sharing no edge: a triangle soup whose coincident corners were not joined; weld them (the command line welds unless --weld off; from arrays: tp_mesh_new_welded, Python tp.weld, C# PolyMesh.Welded; Rhino: Weld) and remesh again",
            input.face_count()
        )));
    }
    Ok(())
}

/// More pieces than this, each of a face or two on average, make [`refuse_crumbs`] call a
/// surface a soup.
const CRUMBS: usize = 16;

/// Options of [`remesh`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct RemeshOptions {
    /// Target quad edge `t` in model units: half a tile length plus a joint (0.145 m for a
    /// 280 x 140 mm tile with a 5 mm joint).
    pub target_edge: f64,
    /// What the orientation field follows.
    pub direction: FieldDirection,
    /// The designer's own field (stress or thrust directions, one vector per input vertex or
    /// face), blended with `direction`'s field by its weight and smoothed with it; `None`
    /// (default) for `direction` alone.
    pub user_field: Option<UserField>,
    /// Polylines the quad rows should follow near them (a ridge, a valley, a line for the
    /// joints), pulled in the same field solve as `user_field`; `None` (default) for none.
    pub guides: Option<GuideCurves>,
    /// Which boundary loops the quads follow (field pinned to the boundary tangents and a
    /// lattice line pinned onto the boundary, so no ragged strip is left along the edge).
    /// `Auto` aligns no loop when `user_field` or `guides` have a share
    /// ([`Self::effective_boundary`]).
    pub boundary: BoundaryAlignment,
    /// Quadrangulate each sheet between the surface's creases on its own (a groin vault's
    /// webs; `mesh::crease`), its field never aligned to the crease; default on. Off, one
    /// field runs over the whole surface, creases or not.
    pub creases: bool,
    /// Run the shape-up step that pulls faces towards squares of side `t`.
    pub shapeup: bool,
    /// Largest distance, as a fraction of `t`, that shape-up may move the surface away from
    /// the input (points are projected back onto the input surface after every iteration, so
    /// this is a safety check on the final result).
    pub shapeup_tolerance: f64,
    /// Number of shape-up iterations.
    pub shapeup_iterations: usize,
    /// Wall-clock limit of [`remesh_with`]: when it passes, the quad mesh as it stands is
    /// returned if there is one (the last fitting rounds and shape-up are cut short),
    /// otherwise [`RemeshError::TimeLimit`]. Default 60 s.
    pub time_limit: Duration,
    /// Strength of the cross field's renormalising steps (Ginzburg-Landau, Viertel and Osting
    /// 2019), which split the turning the boundary forces into separate cones and decide
    /// where they sit: against the smoothness energy of one edge, per vertex. Default
    /// [`RENORMALISATION`]; any finite value from 0 (no renormalisation: the linear
    /// solve's field). Other values give other, equally valid placements of the cones, and
    /// with them other quads: `pipeline::tile_surface_tries` lays the tiles on a few and
    /// keeps the one whose tiles fit best.
    pub renormalisation: f64,
    /// Quads for level courses, shorter along the courses than across them; `None` (default)
    /// for square quads. Set by `pipeline::tile_surface_tries` for a try of its own.
    pub(crate) courses: Option<CourseQuads>,
}

/// Quads laid out for level courses ([`crate::pattern::Courses::Level`]): `target_edge`
/// across the courses (a course's pitch, [`crate::tiles::TileSpec::quad_edge`]) and
/// `along` along them (half a tile and a joint), so that a course's tiles meet at the
/// nominal joint without the fit closing them up. Square quads of a course's pitch are
/// 3.4 % long along the courses for a 280 x 140 mm tile with a 10 mm joint (150 against 145
/// mm): a course open at its ends slides its tiles together and leaves the surplus at the
/// edge, but a course closed on itself (a ring of a tower, a drum, a dome) cannot, and its
/// head joints open to about twice the joint (a tower 6 m across: p95 |gap - joint| 9.4
/// mm; with these quads 0.2 mm). See `position::spacings` for where the lattice takes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CourseQuads {
    /// The up direction the courses are level across (unit).
    pub up: [f64; 3],
    /// The quad edge along the courses, in model units (less than `target_edge`).
    pub along: f64,
}

/// Default [`RemeshOptions::renormalisation`].
pub const RENORMALISATION: f64 = 0.5;

impl Default for RemeshOptions {
    fn default() -> Self {
        Self {
            target_edge: 0.145,
            direction: FieldDirection::Curvature,
            user_field: None,
            guides: None,
            boundary: BoundaryAlignment::Auto,
            creases: true,
            shapeup: false,
            shapeup_tolerance: 0.1,
            shapeup_iterations: 20,
            time_limit: Duration::from_secs(60),
            renormalisation: RENORMALISATION,
            courses: None,
        }
    }
}

impl RemeshOptions {
    /// The boundary alignment in effect: [`BoundaryAlignment::Auto`] aligns no loop when the
    /// designer's field or guide curves have a share (its vectors decide along the boundary
    /// too, where thrust lines meet the supports at their own angle; a guide drawn across a
    /// vault at an angle to its edges would otherwise fight the edges' pinned crosses); an
    /// explicit choice is kept.
    pub fn effective_boundary(&self) -> BoundaryAlignment {
        match self.boundary {
            BoundaryAlignment::Auto if self.designer_pulls() => BoundaryAlignment::Never,
            boundary => boundary,
        }
    }

    /// Whether the designer's field or guide curves have a share in the field.
    pub fn designer_pulls(&self) -> bool {
        self.user_field.as_ref().is_some_and(|f| f.weight > 0.0)
            || self.guides.as_ref().is_some_and(GuideCurves::active)
    }

    /// Converts seconds (as typed on a command line or passed through the C ABI) into a time
    /// limit.
    ///
    /// # Errors
    /// [`RemeshError::BadTimeLimit`] for negative, NaN or overflowing values.
    pub fn time_limit_from_secs(seconds: f64) -> Result<Duration, RemeshError> {
        Duration::try_from_secs_f64(seconds).map_err(|_| RemeshError::BadTimeLimit(seconds))
    }
}

/// The result of [`remesh`]: the quad mesh and its quality numbers.
#[derive(Debug, Clone)]
pub struct Remeshed {
    /// The pure quad mesh, on the input surface.
    pub quads: PolyMesh,
    /// Its acceptance metrics against the input (with the run time in `seconds`).
    pub metrics: Metrics,
}

/// Why [`remesh`] refused or failed.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RemeshError {
    /// The target edge is zero, negative, NaN or infinite.
    #[error("target edge {0} is not a positive finite length")]
    BadTargetEdge(f64),
    /// The target edge is so large that the surface would get almost no quad.
    #[error(
        "target edge {target} is too large for a surface of area {area:.4}: it would get only a few quads (the edge may be at most {max:.4}); the quads are half a tile and a joint long (`run`, the tile stages), so use a smaller tile or edge, or check that the tile and the mesh are in the same units"
    )]
    TargetEdgeTooLarge {
        /// The target edge given.
        target: f64,
        /// The surface area.
        area: f64,
        /// The largest target edge accepted.
        max: f64,
    },
    /// The target edge is so small that the quad mesh would be unreasonably large.
    #[error(
        "target edge {target} would give about {quads:.0} quads on this surface (limit {limit}); use a larger edge"
    )]
    TargetEdgeTooSmall {
        /// The target edge given.
        target: f64,
        /// Estimated number of quads.
        quads: f64,
        /// The largest number of quads accepted.
        limit: usize,
    },
    /// A user direction vector is zero or not finite.
    #[error("field direction vector {0:?} must be finite and non-zero")]
    BadDirection([f64; 3]),
    /// The user field's vector count matches neither the vertices nor the faces.
    #[error(
        "the field has {given} vectors but the mesh has {vertices} vertices and {faces} faces; give one vector per vertex or one per face"
    )]
    FieldCount {
        /// Vectors given.
        given: usize,
        /// Vertices of the input mesh.
        vertices: usize,
        /// Faces of the input mesh.
        faces: usize,
    },
    /// A user field vector is zero or not finite.
    #[error(
        "field vector of {site} {index} is {vector:?}; every vector must be finite and non-zero (give the local direction, any length)"
    )]
    BadFieldVector {
        /// Its index among the vertices or faces.
        index: usize,
        /// Whether it is a vertex or a face.
        site: FieldSite,
        /// The vector given.
        vector: [f64; 3],
    },
    /// The user field's weight is outside `[0, 1]`.
    #[error("field weight {0} must be a number from 0 (curvature only) to 1 (user field only)")]
    BadFieldWeight(f64),
    /// A guide curve has fewer than 2 points.
    #[error(
        "guide curve {curve} has {points} point(s); a guide is a polyline of at least 2 points"
    )]
    GuideTooShort {
        /// Its index among the curves.
        curve: usize,
        /// Its number of points.
        points: usize,
    },
    /// A guide curve's point has a NaN or infinite coordinate.
    #[error(
        "point {point} of guide curve {curve} is {value:?}; every coordinate must be a finite number (model units)"
    )]
    BadGuidePoint {
        /// The curve's index.
        curve: usize,
        /// The point's index along the curve.
        point: usize,
        /// The point given.
        value: [f64; 3],
    },
    /// A guide curve's points all coincide (or its length is not finite).
    #[error(
        "guide curve {curve} has no length (all its points coincide); give at least two distinct points"
    )]
    GuideZeroLength {
        /// The curve's index.
        curve: usize,
    },
    /// No part of a guide curve comes near the surface.
    #[error(
        "guide curve {curve} is nowhere near the surface: its closest point is {distance:.4} away, farther than its reach {reach:.4} (2 target edges); draw or project the curve onto the surface, in the mesh's units"
    )]
    GuideOffSurface {
        /// The curve's index.
        curve: usize,
        /// The least distance of the curve to the surface.
        distance: f64,
        /// The distance within which a curve pulls (2 target edges).
        reach: f64,
    },
    /// The guide curves' weight is outside `[0, 1]`.
    #[error(
        "guide weight {0} must be a number from 0 (guides ignored) to 1 (guides alone near them)"
    )]
    BadGuideWeight(f64),
    /// A rotation angle is not finite.
    #[error("field rotation angle {0} is not finite")]
    BadAngle(f64),
    /// The renormalisation strength is negative, NaN or infinite.
    #[error(
        "renormalisation strength {0} must be a finite number from 0 (the default is {RENORMALISATION})"
    )]
    BadRenormalisation(f64),
    /// A shape-up tolerance or iteration count is unusable.
    #[error("shape-up tolerance {0} must be a positive finite fraction of the target edge")]
    BadShapeupTolerance(f64),
    /// The input has degenerate faces only, or a vertex where the surface pinches.
    #[error("unsupported input surface: {0}")]
    UnsupportedInput(String),
    /// The quad mesh could not be assembled into a valid mesh (a bug or an extreme input).
    /// The mesh error is in the message, not a `source()`, so that a chain of sources
    /// printed after it (`{:#}`) does not say it twice.
    #[error("the quad mesh could not be built: {0}")]
    Mesh(MeshError),
    /// Extraction found no quad at all.
    #[error(
        "no quad could be extracted; the target edge {0} is probably too large for this surface"
    )]
    NothingExtracted(f64),
    /// A time limit that is negative, NaN or too large.
    #[error("time limit {0} s is not a finite number >= 0")]
    BadTimeLimit(f64),
    /// The caller cancelled the stage through its [`crate::control::Control`].
    #[error("remesh cancelled by the caller")]
    Cancelled,
    /// The time limit passed before any quad mesh existed.
    #[error(
        "the remesh time limit passed after {seconds:.2} s, before a quad mesh was ready; allow more time (the command line: --remesh-time-limit of run and demo, --time-limit of remesh)"
    )]
    TimeLimit {
        /// Seconds spent.
        seconds: f64,
    },
}

impl From<MeshError> for RemeshError {
    fn from(error: MeshError) -> Self {
        Self::Mesh(error)
    }
}

/// Most quads [`remesh`] will produce, so a wrong unit (mm for m) fails fast instead of
/// exhausting memory.
pub const MAX_QUADS: usize = 2_000_000;

/// Quadrangulates `input` into near-squares of edge `options.target_edge` (paper section 3.1).
/// Runs without progress reports or cancellation; see [`remesh_with`].
///
/// # Errors
/// As [`remesh_with`].
pub fn remesh(input: &PolyMesh, options: &RemeshOptions) -> Result<Remeshed, RemeshError> {
    remesh_with(input, options, &mut Control::none())
}

/// [`remesh`] reporting progress in `[0, 1]` to `control` (about every 10 ms, on the calling
/// thread) and stopping when it asks to, or when `options.time_limit` has passed: then the
/// quad mesh as it stands is returned if one exists already (the final fitting rounds and
/// shape-up are cut short), otherwise [`RemeshError::TimeLimit`].
///
/// # Errors
/// [`RemeshError`] for bad options (target edge not positive, far too large or small, bad
/// direction), unsupported input (no area, pinched vertices), an extraction failure,
/// [`RemeshError::Cancelled`] when `control` asked to stop and [`RemeshError::TimeLimit`]
/// when the limit passed before any quad mesh existed.
pub fn remesh_with(
    input: &PolyMesh,
    options: &RemeshOptions,
    control: &mut Control<'_>,
) -> Result<Remeshed, RemeshError> {
    let start = Instant::now();
    check_options(input, options)?;
    // Each sheet between creases gets quads of its own (`mesh::crease`).
    let sheets = options
        .creases
        .then(|| crease::split_at_creases(input))
        .flatten();
    let (input, user_field) = match &sheets {
        Some(sheets) => (
            &sheets.mesh,
            options
                .user_field
                .as_ref()
                .map(|u| u.on_copies(&sheets.source)),
        ),
        None => (input, None),
    };
    let user_field = user_field.as_ref().or(options.user_field.as_ref());
    let mut budget = Budget::new(control, start, options.time_limit);
    let t = options.target_edge;
    budget.stage(0.0, 0.02);
    budget.check()?;
    refuse_crumbs(input)?;
    let (mut base, surface_of) = surface::Surface::from_polymesh_mapped(input)?;
    base.set_boundary_scale(t * 0.5);
    let samples = user_field.map(|u| (u.samples(input, &surface_of, base.len()), u.weight));
    let locator = surface::Locator::new(&base);
    let guides = match &options.guides {
        Some(g) if g.active() => Some((g.samples(&base, &locator, t)?, g.weight)),
        _ => None,
    };
    budget.stage(0.02, 0.15);
    // A coarse input (faces of several quads) gets its field solved at the lattice's
    // resolution, from the coarse vertices' data.
    let coarse = refine::subdivide_coarse(&base, t).map(|mut sub| {
        sub.surface.set_boundary_scale(t * 0.5);
        sub
    });
    let (field_surface, principal, samples, guides) = match &coarse {
        Some(sub) => (
            &sub.surface,
            Some(sub.spread_principal(&field::principal_curvatures(
                &base,
                field::CURVATURE_REACH * t,
            ))),
            samples.map(|(s, w)| (sub.spread(&s), w)),
            guides.map(|(s, w)| (sub.spread(&s), w)),
        ),
        None => (&base, None, samples, guides),
    };
    let frames = field::solve(
        field_surface,
        options,
        principal.as_deref(),
        samples.as_ref(),
        guides.as_ref(),
        &mut budget,
    );
    budget.check()?;
    budget.stage(0.15, 0.2);
    let (work, mut work_frames) = refine::refine(field_surface, &frames, t);
    let rotation = match options.direction {
        FieldDirection::Angle(deg) => deg,
        _ => 0.0,
    };
    let aligned = work.aligned_boundary(options.effective_boundary());
    let aligned_boundary = aligned.iter().any(|&a| a);
    field::snap_boundary(&work, &aligned, &mut work_frames, rotation);
    // Lattice lines can lie on the boundary only when the crosses follow it.
    let pin = (rotation / 90.0 - (rotation / 90.0).round()).abs() < 1e-9;
    let pinned: Vec<bool> = aligned.iter().map(|&a| a && pin).collect();
    budget.stage(0.2, 0.8);
    let lattice = position::solve(
        &work,
        &work_frames,
        t,
        options.courses.as_ref(),
        &pinned,
        &mut budget,
    );
    budget.check()?;
    budget.stage(0.8, 0.82);
    let raw = extract::extract(&work, &lattice);
    let coarse_start = lattice.coarse_start;
    if raw.faces.is_empty() {
        return Err(RemeshError::NothingExtracted(t));
    }
    budget.stage(0.82, 0.97);
    let mut quads = cleanup::pure_quads(raw, &locator, t, &mut budget)?;
    if options.shapeup && budget.stopped().is_none() {
        budget.stage(0.97, 0.99);
        quads = shapeup::shapeup(
            &quads,
            &locator,
            t,
            options.shapeup_iterations,
            options.shapeup_tolerance,
            &mut budget,
        )?;
    }
    let quads = PolyMesh::new(quads.positions, quads.faces)?;
    let seconds = start.elapsed().as_secs_f64();
    let mut found = metrics::metrics_with(&locator, input, &quads, t);
    found.seconds = seconds;
    found.crease_sheets = sheets.as_ref().map_or(0, |s| s.count);
    found.coarse_start = coarse_start;
    found.aligned_boundary = aligned_boundary;
    budget.finish();
    Ok(Remeshed {
        quads,
        metrics: found,
    })
}

fn check_options(input: &PolyMesh, options: &RemeshOptions) -> Result<(), RemeshError> {
    let t = options.target_edge;
    if !(t.is_finite() && t > 0.0) {
        return Err(RemeshError::BadTargetEdge(t));
    }
    match options.direction {
        FieldDirection::Vector(v)
            if !v.iter().all(|c| c.is_finite()) || v.iter().all(|&c| c == 0.0) =>
        {
            return Err(RemeshError::BadDirection(v));
        }
        FieldDirection::Angle(a) if !a.is_finite() => return Err(RemeshError::BadAngle(a)),
        _ => {}
    }
    if let Some(field) = &options.user_field {
        field.check(input)?;
    }
    if let Some(guides) = &options.guides {
        guides.check()?;
    }
    if !(options.renormalisation.is_finite() && options.renormalisation >= 0.0) {
        return Err(RemeshError::BadRenormalisation(options.renormalisation));
    }
    if options.shapeup
        && !(options.shapeup_tolerance.is_finite() && options.shapeup_tolerance > 0.0)
    {
        return Err(RemeshError::BadShapeupTolerance(options.shapeup_tolerance));
    }
    let area = input.area();
    if !(area.is_finite() && area > 0.0) {
        return Err(RemeshError::UnsupportedInput(format!(
            "the surface has no area ({area})"
        )));
    }
    // A handful of quads is the least that makes a pattern; below that the lattice
    // cannot resolve the surface.
    let max = (area / 4.0).sqrt();
    if t > max {
        return Err(RemeshError::TargetEdgeTooLarge {
            target: t,
            area,
            max,
        });
    }
    let quads = area / (t * t);
    if quads > MAX_QUADS as f64 {
        return Err(RemeshError::TargetEdgeTooSmall {
            target: t,
            quads,
            limit: MAX_QUADS,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    /// A vertical tube of radius `r` and height `h`, open at both ends, in triangles of
    /// about `edge`.
    fn tube(r: f64, h: f64, edge: f64) -> PolyMesh {
        let around = (std::f64::consts::TAU * r / edge).round() as usize;
        let rows = (h / edge).round() as usize;
        let at = |i: usize, j: usize| j * around + i % around;
        let points = (0..=rows)
            .flat_map(|j| {
                (0..around).map(move |i| {
                    let a =
                        std::f64::consts::TAU * (i as f64 + 0.5 * (j % 2) as f64) / around as f64;
                    Point3::new(r * a.cos(), r * a.sin(), h * j as f64 / rows as f64)
                })
            })
            .collect();
        let mut faces = Vec::new();
        for j in 0..rows {
            for i in 0..around {
                faces.push(vec![at(i, j), at(i + 1, j), at(i, j + 1)]);
                faces.push(vec![at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        PolyMesh::new(points, faces).unwrap()
    }

    /// Mean length of the quad edges that run round a vertical tube (more level than not).
    fn mean_level_edge(quads: &PolyMesh) -> f64 {
        let p = quads.positions();
        let (mut sum, mut n) = (0.0, 0);
        for face in quads.faces() {
            for k in 0..face.len() {
                let d = p[face[(k + 1) % face.len()]] - p[face[k]];
                if d.z.abs() < 0.5 * d.norm() {
                    sum += d.norm();
                    n += 1;
                }
            }
        }
        sum / n as f64
    }

    #[test]
    fn quads_for_level_courses_are_half_a_tile_along_them_and_a_pitch_across() {
        // A tower whose rings hold 30 quads of 0.145 but 29 of 0.15: square quads of a
        // course's pitch make each ring's tiles 10 mm too long, which a closed ring cannot
        // give back at its ends.
        let surface = tube(0.6923, 1.2, 0.05);
        let square = RemeshOptions {
            target_edge: 0.15,
            ..RemeshOptions::default()
        };
        let courses = RemeshOptions {
            courses: Some(CourseQuads {
                up: [0.0, 0.0, 1.0],
                along: 0.145,
            }),
            ..square.clone()
        };
        let along = mean_level_edge(&remesh(&surface, &square).unwrap().quads);
        assert!((along / 0.15 - 1.0).abs() < 0.02, "square quads: {along}");
        let quads = remesh(&surface, &courses).unwrap().quads;
        let along = mean_level_edge(&quads);
        assert!(
            (along / 0.145 - 1.0).abs() < 0.01,
            "courses' quads: {along}"
        );
        // Across the courses they keep the pitch: 8 rows of 0.15 up the 1.2 m.
        let rows = quads.face_count() as f64 / (std::f64::consts::TAU * 0.6923 / along);
        assert!((rows - 8.0).abs() < 0.5, "{rows} rows");
    }
}
