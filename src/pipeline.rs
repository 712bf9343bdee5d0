//! The stages run one after another: a quad mesh in, tiles and their report out. Every front
//! end (CLI, C ABI) calls this rather than chaining the stages itself.

use std::time::Instant;

use thiserror::Error;

use crate::control::Control;
use crate::mesh::{MeshError, PolyMesh};
use crate::pattern::{self, Pattern, PatternError, PatternOptions};
use crate::remesh::{self, RemeshError, RemeshOptions, Remeshed};
use crate::report::Report;
use crate::tiles::{self, CutGroup, DroppedTile, FinishOptions, Tile, TileError, TileSpec};

/// Any stage's error.
#[derive(Debug, Clone, PartialEq, Error)]
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
}

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
    /// Counts, proof status, joint gaps, cutting, laying order, timings.
    pub report: Report,
}

/// All three stages: quadrangulates `surface` with quads of edge `remesh.target_edge`, then
/// matches and tiles them, cutting the tiles to `surface`'s boundary.
///
/// # Errors
/// The first stage error.
pub fn tile_surface(
    surface: &PolyMesh,
    remesh: &RemeshOptions,
    options: &PatternOptions,
    spec: &TileSpec,
    finish: &FinishOptions,
    control: &mut Control<'_>,
) -> Result<(Remeshed, Tiling), Error> {
    spec.validate()?;
    let remeshed = remesh::remesh(surface, remesh)?;
    spec.validate()?;
    let pattern = pattern::solve_with(&remeshed.quads, options, control)?;
    let tiling = tiles_for_pattern(&remeshed.quads, Some(surface), pattern, spec, finish)?;
    Ok((remeshed, tiling))
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
    tiles_for_pattern(quads, surface, pattern, spec, finish)
}

/// Builds the tiles and report for a matching found earlier (e.g. read from `match` JSON),
/// cut to the boundary of `surface` (the quad mesh's own when `None`).
///
/// # Errors
/// An invalid spec or a pattern that does not fit the mesh.
pub fn tiles_for_pattern(quads: &PolyMesh, surface: Option<&PolyMesh>, pattern: Pattern, spec: &TileSpec, finish: &FinishOptions) -> Result<Tiling, Error> {
    let started = Instant::now();
    finish.validate()?;
    let boxes = tiles::build(quads, &pattern, spec)?;
    let (tiles, finished) = tiles::finish(quads, surface, boxes, spec, finish);
    let mut report = Report::new(quads, &pattern, &tiles, spec);
    report.add_finish(&tiles, &finished, surface.unwrap_or(quads));
    report.seconds.tiles = started.elapsed().as_secs_f64();
    Ok(Tiling { pattern, tiles, dropped: finished.dropped, cut_list: finished.cut_list, report })
}
