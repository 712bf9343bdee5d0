//! Gaps and overlaps between neighbouring tiles (paper section 4.1, Figure 8: gaps grow with
//! curvature, because flat boxes cannot follow a doubly curved surface).
//!
//! Every mesh edge between faces of two different tiles is a contact. At the edge's two ends
//! and its midpoint, the gap is the distance from the edge point to the facing side plane of
//! one tile plus the same for the other (positive outside a tile): two tiles laid exactly
//! with the nominal joint show `gap = joint`, and a negative gap is an overlap.

use serde::Serialize;

use crate::mesh::{PolyMesh, Topology};
use crate::tiles::Tile;

/// One contact between two tiles across a mesh edge.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Contact {
    /// The two tiles (indices into the tile list).
    pub tiles: [usize; 2],
    /// The mesh edge's vertices.
    pub edge: [usize; 2],
    /// Gaps at the edge's first end, midpoint and second end.
    pub gaps: [f64; 3],
}

impl Contact {
    /// Smallest gap along the contact (negative: overlap).
    pub fn min_gap(&self) -> f64 {
        self.gaps.iter().copied().fold(f64::INFINITY, f64::min)
    }

    /// Largest gap along the contact.
    pub fn max_gap(&self) -> f64 {
        self.gaps.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }
}

/// Summary of all contacts.
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
    /// 95th percentile of the gap over all sample points.
    pub p95_gap: f64,
    /// 95th percentile of `|gap - joint|` over all sample points.
    pub p95_deviation: f64,
    /// Deepest overlap (0 when no tiles overlap).
    pub max_overlap: f64,
    /// Contacts where the tiles overlap somewhere.
    pub overlaps: usize,
}

/// Measures every tile-to-tile contact, in edge order.
pub fn contacts(mesh: &PolyMesh, tiles: &[Tile]) -> Vec<Contact> {
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut tile_of = vec![None; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = Some(t));
    }
    let mut found = Vec::new();
    for edge in topology.edges() {
        let [f, g] = edge.faces[..] else { continue };
        let (Some(a), Some(b)) = (tile_of[f], tile_of[g]) else { continue };
        if a == b {
            continue;
        }
        let [p, q] = edge.vertices.map(|v| mesh.positions()[v]);
        let gaps = [p, nalgebra::center(&p, &q), q].map(|s| outside_distance(&tiles[a], &s) + outside_distance(&tiles[b], &s));
        found.push(Contact { tiles: [a, b], edge: edge.vertices, gaps });
    }
    found
}

impl JointSummary {
    /// Summarises `contacts` against the nominal `joint`.
    pub fn of(contacts: &[Contact], joint: f64) -> Self {
        let mut samples: Vec<f64> = contacts.iter().flat_map(|c| c.gaps).collect();
        let mut deviations: Vec<f64> = samples.iter().map(|g| (g - joint).abs()).collect();
        samples.sort_by(f64::total_cmp);
        deviations.sort_by(f64::total_cmp);
        let (min_gap, max_gap) = (samples.first().copied().unwrap_or(0.0), samples.last().copied().unwrap_or(0.0));
        Self {
            contacts: contacts.len(),
            joint,
            min_gap,
            max_gap,
            mean_gap: contacts.iter().map(|c| c.gaps[1]).sum::<f64>() / contacts.len().max(1) as f64,
            p95_gap: percentile(&samples, 95),
            p95_deviation: percentile(&deviations, 95),
            max_overlap: (-min_gap).max(0.0),
            overlaps: contacts.iter().filter(|c| c.min_gap() < 0.0).count(),
        }
    }
}

/// The `p`-th percentile of sorted values (nearest rank), 0 for none.
fn percentile(sorted: &[f64], p: usize) -> f64 {
    sorted.get((sorted.len() * p).div_ceil(100).saturating_sub(1)).copied().unwrap_or(0.0)
}

/// Signed distance from `point` to the side plane of `tile` that faces it (positive outside).
/// The facing side is the one the point lies furthest beyond, relative to the half-extents.
fn outside_distance(tile: &Tile, point: &nalgebra::Point3<f64>) -> f64 {
    let local = tile.frame.to_local(point);
    let (hx, hy) = (tile.size[0] / 2.0, tile.size[1] / 2.0);
    if local.x.abs() / hx >= local.y.abs() / hy { local.x.abs() - hx } else { local.y.abs() - hy }
}
