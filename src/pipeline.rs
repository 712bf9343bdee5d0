//! The stages run one after another: a quad mesh in, tiles and their report out. Every front
//! end (CLI, C ABI) calls this rather than chaining the stages itself.

use std::time::Instant;

use thiserror::Error;

use crate::control::Control;
use crate::mesh::{MeshError, PolyMesh};
use crate::pattern::{self, Pattern, PatternError, PatternOptions};
use crate::remesh::{self, RemeshError, RemeshOptions, Remeshed};
use crate::report::Report;
use crate::tiles::{self, Tile, TileError, TileSpec};

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
    /// The placed tiles: full tiles in pair order, then half tiles.
    pub tiles: Vec<Tile>,
    /// Counts, proof status, joint gaps, timings.
    pub report: Report,
}

/// All three stages: quadrangulates `surface` with quads of edge `remesh.target_edge`, then
/// matches and tiles them.
///
/// # Errors
/// The first stage error.
pub fn tile_surface(
    surface: &PolyMesh,
    remesh: &RemeshOptions,
    options: &PatternOptions,
    spec: &TileSpec,
    control: &mut Control<'_>,
) -> Result<(Remeshed, Tiling), Error> {
    spec.validate()?;
    let remeshed = remesh::remesh(surface, remesh)?;
    let tiling = tile_quad_mesh(&remeshed.quads, options, spec, control)?;
    Ok((remeshed, tiling))
}

/// Matches `quads` into tiles and builds the boxes.
///
/// # Errors
/// The first stage error.
pub fn tile_quad_mesh(quads: &PolyMesh, options: &PatternOptions, spec: &TileSpec, control: &mut Control<'_>) -> Result<Tiling, Error> {
    spec.validate()?;
    let pattern = pattern::solve_with(quads, options, control)?;
    tiles_for_pattern(quads, pattern, spec)
}

/// Builds the tiles and report for a matching found earlier (e.g. read from `match` JSON).
///
/// # Errors
/// An invalid spec or a pattern that does not fit the mesh.
pub fn tiles_for_pattern(quads: &PolyMesh, pattern: Pattern, spec: &TileSpec) -> Result<Tiling, Error> {
    let started = Instant::now();
    let tiles = tiles::build(quads, &pattern, spec)?;
    let mut report = Report::new(quads, &pattern, &tiles, spec);
    report.seconds.tiles = started.elapsed().as_secs_f64();
    Ok(Tiling { pattern, tiles, report })
}
