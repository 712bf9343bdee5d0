//! The stages run one after another: a quad mesh in, tiles and their report out. Every front
//! end (CLI, C ABI) calls this rather than chaining the stages itself.

mod tries;

pub use tries::{
    AUTO_TRIES_QUADS, LATER_PATTERN_SECONDS, MAX_TRIES, Tries, score, tile_surface_tries,
};

use std::time::Instant;

use thiserror::Error;

use crate::control::{Control, Figures};
use crate::geom::SurfaceIndex;
use crate::mesh::{MeshError, PolyMesh};
use crate::pattern::{self, Pattern, PatternError, PatternOptions};
use crate::remesh::{self, RemeshError, RemeshOptions, Remeshed};
use crate::report::{self, Joint, JointSummary, Report};
use crate::tiles::{
    self, CutGroup, DroppedTile, FinishOptions, FitStatus, Tile, TileError, TileSpec,
};

/// Any stage's error.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// The mesh was refused.
    #[error(transparent)]
    Mesh(#[from] MeshError),
    /// The pattern stage failed.
    #[error(transparent)]
    Pattern(#[from] PatternError),
    /// The tile stage failed.
    #[error(transparent)]
    Tiles(#[from] TileError),
    /// The remesh stage failed.
    #[error(transparent)]
    Remesh(#[from] RemeshError),
    /// The pattern was made for a mesh with another number of faces.
    #[error(
        "the pattern was made for a mesh of {pattern_faces} faces, but this mesh has {mesh_faces}: give the quad mesh the pattern was solved on"
    )]
    PatternMismatch {
        /// Faces of the mesh the pattern was solved on.
        pattern_faces: usize,
        /// Faces of the mesh given.
        mesh_faces: usize,
    },
    /// The tile is so small next to a mesh's faces that cutting the tiles to the boundary
    /// would need an absurd amount of memory (see [`MAX_GRID_CELLS`]): typically a tile in
    /// metres on a mesh in millimetres.
    #[error(
        "tile length {length:?} is tiny next to face {face} of the {mesh}, which spans {span:?} along one axis: cutting the tiles would need about {cells:.3e} grid cells (at most {limit:.3e}); are the tile and the mesh in the same units?"
    )]
    TileTooSmall {
        /// `"quad mesh"` or `"surface"`.
        mesh: &'static str,
        /// The face spanning the most grid cells.
        face: usize,
        /// Its largest extent along a coordinate axis.
        span: f64,
        /// The tile length.
        length: f64,
        /// Grid cells the boundary search would need.
        cells: f64,
        /// The limit for these meshes.
        limit: f64,
    },
}

impl Error {
    /// The error with the faces of the quad mesh it names numbered as in the file
    /// `numbering` traces (see [`PatternError::in_file_numbers`]).
    pub fn in_file_numbers(self, numbering: &crate::mesh::FileNumbering) -> Self {
        match self {
            Error::Pattern(e) => Error::Pattern(e.in_file_numbers(numbering)),
            Error::Tiles(e) => Error::Tiles(e.in_file_numbers(numbering)),
            other => other,
        }
    }
}

/// Grid cells (of a tile's size) that cutting tiles to a boundary may take: every face and
/// every boundary edge is entered in each cell its bounding box meets, so a tile much smaller
/// than the faces (a unit mistake) would need memory by the gigabyte and minutes of hashing.
/// Meshes whose faces are about half a tile, as the remesher makes them, use at most 8 cells
/// per face and as many per boundary edge; the limit is this or [`GRID_CELLS_PER_FACE`] per
/// face, whichever is larger.
pub const MAX_GRID_CELLS: f64 = 4e6;

/// Grid cells per face always allowed (see [`MAX_GRID_CELLS`]).
pub const GRID_CELLS_PER_FACE: f64 = 64.0;

/// The result of the whole pipeline.
#[derive(Debug, Clone)]
pub struct Tiling {
    /// The matching.
    pub pattern: Pattern,
    /// The placed tiles, cut to the surface, labelled and numbered in laying order: full
    /// tiles in pair order, then half tiles (boundary tiles stay in their place).
    pub tiles: Vec<Tile>,
    /// Tiles left out: off the surface, or slivers.
    pub dropped: Vec<DroppedTile>,
    /// Cut shapes with counts and labels.
    pub cut_list: Vec<CutGroup>,
    /// Every joint between neighbouring tiles (indices into `tiles`), as the report measures
    /// them.
    pub joints: Vec<Joint>,
    /// Counts, proof status, joint gaps, cutting, laying order, timings.
    pub report: Report,
}

impl Tiling {
    /// Each tile's worst joint: the largest `|gap - joint|` over the joints it takes part in
    /// (0 for a tile with none).
    pub fn joint_deviations(&self) -> Vec<f64> {
        let mut worst = vec![0.0_f64; self.tiles.len()];
        for j in &self.joints {
            for t in j.tiles {
                worst[t] = worst[t].max((j.gap - self.report.tile.joint).abs());
            }
        }
        worst
    }
}

/// All three stages: quadrangulates `surface` with quads of edge `remesh.target_edge`, then
/// matches and tiles them, cutting the tiles to `surface`'s boundary. `control` hears the
/// remesh stage as fractions `0..0.5` and the pattern stage as `0.5..1`, and can cancel
/// either.
///
/// Zones (`options.zones`) and excluded faces (`options.excluded_faces`: openings, areas
/// laid by hand) are given per face of `surface`, since the quads do not exist yet: each
/// quad takes the zone of the surface face closest to its centroid ([`zones_on_quads`]), and
/// is left out when that face is; forced pairs would name quads, and are the caller's to
/// refuse (the C ABI and the command line do).
///
/// # Errors
/// The first stage error; a bad tile or finishing option, pattern options that are bad
/// whatever the mesh ([`PatternOptions::check`]) and zones not one per face of `surface`
/// ([`PatternError::ZoneCount`]) or excluded faces beyond them fail before the remesh.
pub fn tile_surface(
    surface: &PolyMesh,
    remesh: &RemeshOptions,
    options: &PatternOptions,
    spec: &TileSpec,
    finish: &FinishOptions,
    control: &mut Control<'_>,
) -> Result<(Remeshed, Tiling), Error> {
    spec.validate()?;
    finish.validate()?;
    options.check()?;
    if let Some(zones) = &options.zones {
        pattern::check_zone_count(zones.len(), surface.face_count())?;
    }
    if let Some(&face) = options
        .excluded_faces
        .iter()
        .find(|&&f| f >= surface.face_count())
    {
        return Err(PatternError::FaceOutOfRange {
            face,
            face_count: surface.face_count(),
        }
        .into());
    }
    // Before the long stages: a tile far too small for the surface fails at once.
    check_tile_scale(None, Some(surface), spec)?;
    // Progress: the remesh stage reports the first half, the pattern stage the second.
    let remeshed = {
        let mut first_half = |fraction: f64| control.keep_going(0.5 * fraction);
        remesh::remesh_with(
            surface,
            remesh,
            &mut Control::with_progress(&mut first_half),
        )?
    };
    // The surface's zones and excluded faces carried over to the quads.
    let left_out: &[usize] = &options.excluded_faces;
    let zoned;
    let options = if options.zones.is_some() || !options.excluded_faces.is_empty() {
        // One closest-face search serves both (the zone count was checked above).
        let nearest = nearest_surface_faces(surface, &remeshed.quads);
        let zones = options
            .zones
            .as_ref()
            .map(|zones| nearest.iter().map(|&f| zones[f]).collect());
        let mut left_out = vec![false; surface.face_count()];
        options
            .excluded_faces
            .iter()
            .for_each(|&f| left_out[f] = true);
        let excluded_faces = (0..nearest.len())
            .filter(|&q| left_out[nearest[q]])
            .collect();
        zoned = PatternOptions {
            zones,
            excluded_faces,
            ..options.clone()
        };
        &zoned
    } else {
        options
    };
    let pattern = {
        // The pattern stage's figures (best, bound) go on to the caller's control.
        let mut second_half = |fraction: f64, figures: Option<Figures>| {
            if let Some(figures) = figures {
                control.note(figures);
            }
            control.keep_going(0.5 + 0.5 * fraction)
        };
        pattern::solve_with(
            &remeshed.quads,
            options,
            &mut Control::with_figures(&mut second_half),
        )?
    };
    // The fit stage is fast next to the others: it reports as done, and can still cancel.
    let mut last = |_: f64| control.keep_going(1.0);
    let finish = with_bond(finish, options.bond);
    // The excluded area is the caller's own faces here, not the quads' approximation of
    // them: the opening, the tear fill and the coverage all take it.
    let excluded = tiles::ExcludedArea::new(surface, left_out);
    let opened = tiles::without_faces(surface, left_out);
    let tiling = lay_tiles(
        &remeshed.quads,
        Some(surface),
        LeftOut {
            area: excluded.as_ref(),
            opened: opened.as_ref(),
        },
        pattern,
        spec,
        &finish,
        &mut Control::with_progress(&mut last),
    )?;
    Ok((remeshed, tiling))
}

/// Zones of a quad mesh from zones of the surface it was remeshed from: each quad takes the
/// zone of the face of `surface` closest to its centroid (ties go to the lower face), so a
/// band of faces tagged on the designer's surface becomes a band of quads.
///
/// # Errors
/// [`PatternError::ZoneCount`] when `zones` does not give one zone per face of `surface`.
pub fn zones_on_quads<T: Copy>(
    surface: &PolyMesh,
    zones: &[T],
    quads: &PolyMesh,
) -> Result<Vec<T>, Error> {
    pattern::check_zone_count(zones.len(), surface.face_count())?;
    Ok(nearest_surface_faces(surface, quads)
        .into_iter()
        .map(|f| zones[f])
        .collect())
}

/// For each quad of `quads`, the face of `surface` closest to its centroid (ties go to the
/// lower face): how data given per surface face reaches the quads.
fn nearest_surface_faces(surface: &PolyMesh, quads: &PolyMesh) -> Vec<usize> {
    let index = SurfaceIndex::from_polymesh(surface);
    let face_of = SurfaceIndex::polymesh_faces(surface);
    (0..quads.face_count())
        .map(|q| {
            let on = index
                .closest(&quads.face_centroid(q).coords)
                .expect("a PolyMesh has faces");
            face_of[on.triangle]
        })
        .collect()
}

/// Matches `quads` into tiles and builds the boxes, cut to the boundary of `surface` (the
/// quad mesh's own when `None`).
///
/// # Errors
/// The first stage error.
pub fn tile_quad_mesh(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    options: &PatternOptions,
    spec: &TileSpec,
    finish: &FinishOptions,
    control: &mut Control<'_>,
) -> Result<Tiling, Error> {
    spec.validate()?;
    let pattern = pattern::solve_with(quads, options, control)?;
    let mut last = |_: f64| control.keep_going(1.0);
    tiles_for_pattern_with(
        quads,
        surface,
        pattern,
        spec,
        &with_bond(finish, options.bond),
        &mut Control::with_progress(&mut last),
    )
}

/// Builds the tiles and report for a matching found earlier (e.g. read from `match` JSON),
/// cut to the boundary of `surface` (the quad mesh's own when `None`).
///
/// # Errors
/// An invalid spec or finishing option, a pattern that does not fit the mesh
/// ([`Error::PatternMismatch`], [`TileError`]), a tile far too small for the meshes
/// ([`Error::TileTooSmall`]).
pub fn tiles_for_pattern(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    pattern: Pattern,
    spec: &TileSpec,
    finish: &FinishOptions,
) -> Result<Tiling, Error> {
    tiles_for_pattern_with(quads, surface, pattern, spec, finish, &mut Control::none())
}

/// [`tiles_for_pattern`], reporting the fit stage's progress to `control`, which can cancel
/// it (the placement so far is kept and the report's `fit.status` says so).
///
/// # Errors
/// As [`tiles_for_pattern`].
pub fn tiles_for_pattern_with(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    pattern: Pattern,
    spec: &TileSpec,
    finish: &FinishOptions,
    control: &mut Control<'_>,
) -> Result<Tiling, Error> {
    // The pattern's excluded quads open the surface where they lie (its faces over them).
    let excluded = tiles::ExcludedArea::new(quads, &pattern.excluded);
    let opened = excluded
        .as_ref()
        .and_then(|e| e.opened(surface.unwrap_or(quads)));
    lay_tiles(
        quads,
        surface,
        LeftOut {
            area: excluded.as_ref(),
            opened: opened.as_ref(),
        },
        pattern,
        spec,
        finish,
        control,
    )
}

/// The area the caller left out of the pattern, when there is one.
#[derive(Clone, Copy)]
struct LeftOut<'a> {
    /// Neither filled nor counted as uncovered.
    area: Option<&'a tiles::ExcludedArea>,
    /// The surface (the quads without one) opened there: the fit keeps the tiles out of it
    /// as out of any opening, and they are cut to its edge.
    opened: Option<&'a PolyMesh>,
}

/// [`tiles_for_pattern_with`] with the area the caller left out ([`LeftOut`]).
fn lay_tiles(
    quads: &PolyMesh,
    surface: Option<&PolyMesh>,
    left_out: LeftOut<'_>,
    pattern: Pattern,
    spec: &TileSpec,
    finish: &FinishOptions,
    control: &mut Control<'_>,
) -> Result<Tiling, Error> {
    let started = Instant::now();
    // The tile first: finishing options default to fractions of it.
    spec.validate()?;
    finish.validate()?;
    if pattern.faces != quads.face_count() {
        return Err(Error::PatternMismatch {
            pattern_faces: pattern.faces,
            mesh_faces: quads.face_count(),
        });
    }
    check_tile_scale(Some(quads), surface, spec)?;
    let boxes = tiles::build(quads, &pattern, spec)?;
    let mm = finish.units_per_mm;
    // The caller's excluded area: openings, areas laid by hand, neither filled nor counted
    // as uncovered; the fit and the cut to the boundary take the surface opened there.
    let (excluded, laid_on) = (left_out.area, left_out.opened.or(surface));
    let (boxes, fitted) = match &finish.fit {
        Some(options) => {
            let before = JointSummary::of(
                &report::gaps::joints(quads, &boxes, spec.joint),
                spec.joint,
                mm,
            );
            let fit_started = Instant::now();
            // Tiles are placed on the sheet they lie on: across a crease the surface's normals
            // would blend the two sheets' and tilt the tiles next to it. Without a surface the
            // quads are the surface, as the tile boundary takes them.
            let sheets = finish
                .creases
                .then(|| crate::mesh::crease::split_at_creases(laid_on.unwrap_or(quads)))
                .flatten();
            let on = sheets.as_ref().map(|s| &s.mesh).or(laid_on);
            let (moved, summary) = tiles::fit::fit(quads, on, boxes, spec, options, control)?;
            (
                moved,
                Some((before, summary, fit_started.elapsed().as_secs_f64())),
            )
        }
        None => (boxes, None),
    };
    // The fill of the fit's tears honours the fit's time limit (a clock of its own, so that
    // a fit stopped by the limit still has its tears filled) and the caller's cancel. The
    // clock starts when the fill does (its first question), not with the clipping and
    // fillers along the edge before it: on a fine input (a million triangles) those take
    // longer than the limit, which then stopped the fill before its first piece.
    let mut fill_started: Option<Instant> = None;
    let fill_limit = finish.fit.map_or(f64::INFINITY, |f| f.time_limit);
    let mut fill_timed_out = false;
    let (tiles, finished) =
        tiles::finish_with(quads, laid_on, boxes, spec, finish, excluded, &mut || {
            let started = *fill_started.get_or_insert_with(Instant::now);
            fill_timed_out = started.elapsed().as_secs_f64() > fill_limit;
            !fill_timed_out && control.keep_going(1.0)
        });
    let joints = report::gaps::joints(quads, &tiles, spec.joint);
    let mut report = Report::measured(quads, &pattern, &tiles, &joints, spec, mm);
    if let Some((before, mut summary, seconds)) = fitted {
        if finished.tear_fill_stopped {
            summary.status = if fill_timed_out {
                FitStatus::TimeLimit
            } else {
                FitStatus::Cancelled
            };
        }
        report.joints.before_fit = Some(Box::new(before));
        report.fit = Some(summary);
        report.seconds.fit = seconds;
    }
    report.add_finish(&tiles, &finished, surface.unwrap_or(quads), excluded);
    report.warnings = report::warnings::check(
        quads,
        surface.unwrap_or(quads),
        spec,
        &finish.sequence.up,
        &report,
    );
    report.seconds.tiles = started.elapsed().as_secs_f64();
    Ok(Tiling {
        pattern,
        tiles,
        dropped: finished.dropped,
        cut_list: finished.cut_list,
        joints,
        report,
    })
}

/// `finish` with its fit keeping `bond`, the bond the pattern was matched for.
pub fn with_bond(finish: &FinishOptions, bond: pattern::Bond) -> FinishOptions {
    let mut finish = *finish;
    if let Some(fit) = finish.fit.as_mut() {
        fit.bond = bond;
    }
    finish
}

/// Refuses a tile far smaller than the faces of `quads` or `surface` before cutting builds its
/// grids of tile-sized cells (see [`MAX_GRID_CELLS`]).
fn check_tile_scale(
    quads: Option<&PolyMesh>,
    surface: Option<&PolyMesh>,
    spec: &TileSpec,
) -> Result<(), Error> {
    // The smallest cell any grid of the tile stage uses.
    let cell = spec.length.max(spec.width);
    let meshes = [("quad mesh", quads), ("surface", surface)];
    let faces: usize = meshes
        .iter()
        .filter_map(|(_, m)| m.map(PolyMesh::face_count))
        .sum();
    let limit = MAX_GRID_CELLS.max(GRID_CELLS_PER_FACE * faces as f64);
    // Cells a box meets; NaN only when a ratio overflowed: as bad as it gets.
    let cells_of = |points: &mut dyn Iterator<Item = nalgebra::Point3<f64>>| -> (f64, f64) {
        let first = points.next().expect("faces and edges have points");
        let (lo, hi) = points.fold((first, first), |(lo, hi), p| (lo.inf(&p), hi.sup(&p)));
        let cells: f64 = (0..3)
            .map(|k| (hi[k] / cell).floor() - (lo[k] / cell).floor() + 1.0)
            .product();
        (
            if cells.is_nan() { f64::INFINITY } else { cells },
            (hi - lo).amax(),
        )
    };
    let mut cells = 0.0;
    let mut worst = (0.0, "quad mesh", 0, 0.0);
    for (name, mesh) in meshes {
        let Some(mesh) = mesh else { continue };
        let topology =
            crate::mesh::Topology::new(mesh).expect("a PolyMesh is manifold by construction");
        for f in 0..mesh.face_count() {
            let (mut here, span) = cells_of(&mut mesh.face_points(f));
            // The face's boundary edges are entered in the boundary grid too.
            for &e in topology
                .face_edges(f)
                .iter()
                .filter(|&&e| topology.edges()[e].is_boundary())
            {
                let [a, b] = topology.edges()[e].vertices;
                here += cells_of(&mut [mesh.positions()[a], mesh.positions()[b]].into_iter()).0;
            }
            cells += here;
            if here > worst.0 {
                worst = (here, name, f, span);
            }
        }
    }
    if cells > limit {
        let (_, mesh, face, span) = worst;
        return Err(Error::TileTooSmall {
            mesh,
            face,
            span,
            length: spec.length,
            cells,
            limit,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;
    use crate::pattern::Bond;

    /// The 280 x 140 x 15 mm tile with a 10 mm joint, in metres.
    fn spec() -> TileSpec {
        TileSpec {
            length: 0.28,
            width: 0.14,
            thickness: 0.015,
            joint: 0.01,
        }
    }

    /// The error of [`tile_surface`] on `surface` with `options`, given a target edge the
    /// remesher would refuse: what fails before the remesh fails first.
    fn error_before_the_remesh(surface: &PolyMesh, options: &PatternOptions) -> Error {
        let remesh = RemeshOptions {
            target_edge: f64::NAN,
            ..RemeshOptions::default()
        };
        let spec = spec();
        tile_surface(
            surface,
            &remesh,
            options,
            &spec,
            &FinishOptions::for_spec(&spec),
            &mut Control::none(),
        )
        .unwrap_err()
    }

    #[test]
    fn quads_take_the_zone_of_the_surface_face_under_their_centroid() {
        // A 12 x 12 triangle surface (two triangles per unit square) tagged by column: the
        // band 4 <= x < 8 is zone 1, the rest 0; quads of 2 x 2 units over it, shifted
        // up by 0.3 off the plane.
        let surface = generate::triangulate_quads(&generate::grid(12, 12));
        let zones: Vec<u8> = (0..surface.face_count())
            .map(|t| {
                let x = (t / 2) % 12;
                u8::from((4..8).contains(&x))
            })
            .collect();
        let coarse = generate::grid(6, 6);
        let quads = PolyMesh::new(
            coarse
                .positions()
                .iter()
                .map(|p| nalgebra::Point3::new(2.0 * p.x, 2.0 * p.y, 0.3))
                .collect(),
            coarse.faces().to_vec(),
        )
        .unwrap();
        let on_quads = zones_on_quads(&surface, &zones, &quads).unwrap();
        let expected: Vec<u8> = (0..36)
            .map(|q| u8::from((2..4).contains(&(q % 6))))
            .collect();
        assert_eq!(on_quads, expected);
    }

    #[test]
    fn zones_not_one_per_surface_face_fail_before_the_remesh() {
        let surface = generate::triangulate_quads(&generate::grid(4, 4));
        let quads = generate::grid(2, 2);
        let err = zones_on_quads(&surface, &[0_u8; 31], &quads).unwrap_err();
        assert_eq!(
            err,
            Error::Pattern(PatternError::ZoneCount {
                given: 31,
                faces: 32
            })
        );
        let options = PatternOptions {
            zones: Some(vec![Bond::Stack; 16]),
            ..PatternOptions::default()
        };
        let err = error_before_the_remesh(&surface, &options);
        assert!(
            err.to_string().contains("16 bonds for a mesh of 32 faces"),
            "{err}"
        );
    }

    #[test]
    fn pattern_options_bad_whatever_the_mesh_fail_before_the_remesh() {
        let surface = generate::triangulate_quads(&generate::grid(4, 4));
        let level = crate::pattern::Courses::Level {
            up: [0.0, 0.0, 1.0],
        };
        let mut zones = vec![Bond::Staggered { weight: 0.5 }; 32];
        zones[7] = Bond::Herringbone { weight: 0.5 };
        let mut bad_zone = vec![Bond::Stack; 32];
        bad_zone[5] = Bond::RunningBond { weight: -1.0 };
        for (options, want) in [
            (
                PatternOptions {
                    zones: Some(zones),
                    courses: level,
                    ..PatternOptions::default()
                },
                PatternError::BondAcrossCourses {
                    bond: "herringbone",
                },
            ),
            (
                PatternOptions {
                    zones: Some(bad_zone),
                    ..PatternOptions::default()
                },
                PatternError::InvalidZone {
                    face: 5,
                    reason: PatternError::InvalidWeight { weight: -1.0 }.to_string(),
                },
            ),
            (
                PatternOptions {
                    gap: 2.0,
                    ..PatternOptions::default()
                },
                PatternError::InvalidGap { gap: 2.0 },
            ),
        ] {
            let err = error_before_the_remesh(&surface, &options);
            assert_eq!(err, Error::Pattern(want));
        }
    }
}
