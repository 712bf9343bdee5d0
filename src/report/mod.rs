//! Quality report of a tiling: counts, the matching's proof status, and how far each joint
//! between neighbouring tiles is from the nominal mortar width (paper section 4.1 / Figure 8:
//! gaps grow with curvature).

pub mod svg;

use serde::Serialize;

use crate::mesh::{PolyMesh, Topology};
use crate::pattern::{Pattern, SolveStatus};
use crate::tiles::{Tile, TileKind, TileSpec};

/// Wall-clock seconds per stage.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StageSeconds {
    /// Pattern (matching) stage.
    pub pattern: f64,
    /// Tile stage.
    pub tiles: f64,
}

/// Gaps between neighbouring tiles, measured across each mesh edge that separates two
/// different tiles.
///
/// At the edge's two ends and its midpoint, the gap is the distance from the edge point to
/// the facing side plane of one tile plus the same for the other (positive outside a tile),
/// so two tiles laid exactly with the nominal joint show `gap = joint`, and a negative gap
/// is an overlap.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JointSummary {
    /// Mesh edges between two different tiles.
    pub contacts: usize,
    /// Nominal joint width.
    pub joint: f64,
    /// Smallest gap at any sample point (negative: overlap).
    pub min_gap: f64,
    /// Largest gap at any sample point.
    pub max_gap: f64,
    /// Mean gap at the edge midpoints.
    pub mean_gap: f64,
    /// 95th percentile of `|gap - joint|` over all sample points.
    pub p95_deviation: f64,
    /// Contacts where the tiles overlap somewhere.
    pub overlaps: usize,
}

/// Everything a designer wants to know about a tiling, serialised as `report.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Faces of the quad mesh.
    pub faces: usize,
    /// Standard tiles (matched pairs).
    pub full_tiles: usize,
    /// Half tiles (unmatched quads), each needs a cut.
    pub half_tiles: usize,
    /// Faces that are not quads: no tile was placed on them.
    pub non_quad_faces: usize,
    /// Faces excluded by the caller.
    pub excluded_faces: usize,
    /// Continuous joints left in the pattern.
    pub continuous_joints: usize,
    /// Shifted (running-bond) pairs in the pattern.
    pub shifted_pairs: usize,
    /// Objective of the matching.
    pub objective: f64,
    /// Proven bound on the objective.
    pub bound: f64,
    /// Relative gap between objective and bound.
    pub gap: f64,
    /// Whether the matching is proven optimal.
    pub status: SolveStatus,
    /// Tile size used.
    pub tile: TileSpec,
    /// Joint gaps and overlaps.
    pub joints: JointSummary,
    /// Seconds per stage.
    pub seconds: StageSeconds,
}

impl Report {
    /// Summarises a tiling built from `pattern` on `mesh`.
    pub fn new(mesh: &PolyMesh, pattern: &Pattern, tiles: &[Tile], spec: &TileSpec) -> Self {
        let count = |kind| tiles.iter().filter(|t| t.kind == kind).count();
        Self {
            faces: mesh.face_count(),
            full_tiles: count(TileKind::Full),
            half_tiles: count(TileKind::Half),
            non_quad_faces: pattern.non_quad.len(),
            excluded_faces: pattern.excluded.len(),
            continuous_joints: pattern.continuous_joints,
            shifted_pairs: pattern.shifted_pairs,
            objective: pattern.objective,
            bound: pattern.bound,
            gap: pattern.gap,
            status: pattern.status,
            tile: *spec,
            joints: joint_summary(mesh, tiles, spec.joint),
            seconds: StageSeconds { pattern: pattern.seconds, tiles: 0.0 },
        }
    }
}

/// Measures every tile-to-tile contact (see [`JointSummary`]).
fn joint_summary(mesh: &PolyMesh, tiles: &[Tile], joint: f64) -> JointSummary {
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut tile_of = vec![None; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = Some(t));
    }
    let (mut contacts, mut overlaps) = (0, 0);
    let (mut min_gap, mut max_gap, mut mid_sum) = (f64::INFINITY, f64::NEG_INFINITY, 0.0);
    let mut deviations = Vec::new();
    for edge in topology.edges() {
        let [f, g] = edge.faces[..] else { continue };
        let (Some(a), Some(b)) = (tile_of[f], tile_of[g]) else { continue };
        if a == b {
            continue;
        }
        let [p, q] = edge.vertices.map(|v| mesh.positions()[v]);
        let samples = [p, nalgebra::center(&p, &q), q];
        let gaps = samples.map(|s| outside_distance(&tiles[a], &s) + outside_distance(&tiles[b], &s));
        contacts += 1;
        mid_sum += gaps[1];
        let lowest = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        overlaps += usize::from(lowest < 0.0);
        min_gap = min_gap.min(lowest);
        max_gap = gaps.iter().copied().fold(max_gap, f64::max);
        deviations.extend(gaps.iter().map(|g| (g - joint).abs()));
    }
    deviations.sort_by(f64::total_cmp);
    let p95_deviation = deviations.get((deviations.len() * 95).div_ceil(100).saturating_sub(1)).copied().unwrap_or(0.0);
    if contacts == 0 {
        (min_gap, max_gap) = (0.0, 0.0);
    }
    JointSummary { contacts, joint, min_gap, max_gap, mean_gap: mid_sum / contacts.max(1) as f64, p95_deviation, overlaps }
}

/// Signed distance from `point` to the side plane of `tile` that faces it (positive outside).
/// The facing side is the one the point lies furthest beyond, relative to the half-extents.
fn outside_distance(tile: &Tile, point: &nalgebra::Point3<f64>) -> f64 {
    let local = tile.frame.to_local(point);
    let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
    if local.x.abs() / hx >= local.y.abs() / hy { local.x.abs() - hx } else { local.y.abs() - hy }
}
