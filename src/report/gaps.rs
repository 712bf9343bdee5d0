//! Joints between neighbouring tiles, as a mason meets them: for every pair of tiles that
//! meet (their faces share a mesh edge) and every other pair that comes within three joints
//! of each other (filler pieces included), the
//! signed separation of their outlines in their mean plane
//! ([`crate::tiles::outline::separation`]): the joint's width where positive, the depth of
//! an overlap where negative. Paper section 4.1, Figure 8: with the section 3.5 placement
//! gaps grow with curvature and quads off the half tile's size make tiles overlap; the fit
//! stage ([`crate::tiles::fit`]) brings them back to the nominal joint.

use std::collections::BTreeSet;

use nalgebra::Point3;
use serde::Serialize;

use crate::geom::HashGrid;
use crate::mesh::{PolyMesh, Topology};
use crate::tiles::{Tile, outline};

/// The joint between two neighbouring tiles.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Joint {
    /// The two tiles (indices into the tile list), the smaller first.
    pub tiles: [usize; 2],
    /// Signed separation of their outlines: the joint's width, or an overlap when negative.
    pub gap: f64,
}

/// Summary of all joints against the nominal joint width.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JointSummary {
    /// Neighbouring pairs of tiles (see [`joints`]).
    pub contacts: usize,
    /// Nominal joint width.
    pub joint: f64,
    /// Narrowest joint (negative: an overlap).
    pub min_gap: f64,
    /// Widest joint.
    pub max_gap: f64,
    /// Mean joint.
    pub mean_gap: f64,
    /// 95th percentile of the joints.
    pub p95_gap: f64,
    /// 95th percentile of `|gap - joint|`.
    pub p95_deviation: f64,
    /// Deepest overlap (0 when no tiles overlap).
    pub max_overlap: f64,
    /// Pairs of tiles that overlap.
    pub overlaps: usize,
    /// Share of pairs with `|gap - joint|` at most 2 mm.
    pub within_2mm: f64,
    /// Share of pairs with `|gap - joint|` at most 5 mm.
    pub within_5mm: f64,
    /// Tiles the fit stage cut because they could not be made to fit (kind `fit_cut`: full
    /// and half tiles that would otherwise need no further cut; filler pieces and tiles cut
    /// to the boundary that the fit trims too are cut anyway and not counted).
    pub fit_cuts: usize,
    /// The same figures for the section 3.5 placement, before the fit stage moved the tiles
    /// (absent when the fit stage did not run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub before_fit: Option<Box<JointSummary>>,
}

/// Every joint of `tiles` placed on `mesh`, in index order: pairs of tiles whose faces share
/// a mesh edge (unless parted by more than three joints with a third tile between them, on
/// the line between their origins), pairs of any tiles (filler pieces too) that overlap, and
/// pairs that come
/// within three joints of each other (with `joint` 0: three hundredths of the widest tile)
/// along a stretch of at least a quarter of the narrower one's width (tiles that only meet
/// at a corner share no joint).
pub fn joints(mesh: &PolyMesh, tiles: &[Tile], joint: f64) -> Vec<Joint> {
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let mut tile_of = vec![usize::MAX; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = t);
    }
    let mut meeting: BTreeSet<[usize; 2]> = BTreeSet::new();
    for edge in topology.edges() {
        if let [f, g] = edge.faces[..] {
            let (a, b) = (tile_of[f], tile_of[g]);
            if a != usize::MAX && b != usize::MAX && a != b {
                meeting.insert([a.min(b), a.max(b)]);
            }
        }
    }
    let outlines: Vec<Vec<Point3<f64>>> = tiles.iter().map(outline::world_corners).collect();
    let reach = tiles
        .iter()
        .map(|t| t.size[0].hypot(t.size[1]))
        .fold(0.0, f64::max);
    let near = 3.0 * joint.max(tiles.iter().map(|t| t.size[1]).fold(0.0, f64::max) / 100.0);
    let separation = |a: usize, b: usize| {
        outline::separation_of(&tiles[a], &outlines[a], &tiles[b], &outlines[b])
    };
    let gap = |a: usize, b: usize| separation(a, b).gap;
    let grid =
        (reach > 0.0).then(|| HashGrid::of_points(reach, tiles.iter().map(|t| [t.frame.origin])));
    // Each tile's and each pair's question stands alone: on the threads of `parallel`,
    // gathered in order.
    let mut found: Vec<Joint> = match &grid {
        Some(grid) => crate::parallel::map(tiles.len(), |a| {
            grid.near(&tiles[a].frame.origin, reach)
                .into_iter()
                .filter(|&b| {
                    b > a
                        && !meeting.contains(&[a, b])
                        && outline::may_touch(&tiles[a], &tiles[b], near)
                })
                .filter_map(|b| {
                    let s = separation(a, b);
                    (s.gap < 0.0 || (s.gap < near && s.shares_joint(&tiles[a], &tiles[b])))
                        .then_some(Joint {
                            tiles: [a, b],
                            gap: s.gap,
                        })
                })
                .collect::<Vec<_>>()
        })
        .into_iter()
        .flatten()
        .collect(),
        None => Vec::new(),
    };
    // Tiles on neighbouring faces parted by a tear share no joint when a piece filling the
    // tear ([`crate::tiles`]' tear fill) lies between them, on the line between their
    // origins: their joints are with that piece, found above. The line is read every half
    // tile width (a far-parted pair may have several pieces between them, and the gaps
    // between pieces), each point taken onto each nearby tile's plane (on a curved surface
    // the chord between two far-parted tiles runs under the pieces between them, on a 20 m
    // dome further than a tile's half width) and counted as covered within half a joint of
    // its outline (a point may fall on a joint between two pieces).
    let parted = |a: usize, b: usize| {
        let (pa, pb) = (tiles[a].frame.origin, tiles[b].frame.origin);
        let step = tiles[a].size[1].min(tiles[b].size[1]) / 2.0;
        let points = ((pb - pa).norm() / step.max(f64::MIN_POSITIVE))
            .ceil()
            .clamp(1.0, 64.0) as usize;
        grid.as_ref().is_some_and(|grid| {
            (1..=points).any(|k| {
                let at = pa + (pb - pa) * (k as f64 / (points + 1) as f64);
                grid.near(&at, reach).into_iter().any(|c| {
                    let frame = &tiles[c].frame;
                    let onto = at + frame.z * frame.z.dot(&(frame.origin - at));
                    c != a && c != b && outline::covers(&tiles[c], &onto, joint / 2.0)
                })
            })
        })
    };
    let meeting: Vec<[usize; 2]> = meeting.into_iter().collect();
    found.extend(
        crate::parallel::map(meeting.len(), |k| {
            let [a, b] = meeting[k];
            let gap = gap(a, b);
            (gap < near || !parted(a, b)).then_some(Joint { tiles: [a, b], gap })
        })
        .into_iter()
        .flatten(),
    );
    found.sort_by_key(|j| j.tiles);
    found
}

impl JointSummary {
    /// Summarises `joints` against the nominal `joint`, with `mm` model units per millimetre.
    pub fn of(joints: &[Joint], joint: f64, mm: f64) -> Self {
        let mut gaps: Vec<f64> = joints.iter().map(|j| j.gap).collect();
        let mut deviations: Vec<f64> = gaps.iter().map(|g| (g - joint).abs()).collect();
        gaps.sort_by(f64::total_cmp);
        deviations.sort_by(f64::total_cmp);
        let share = |limit: f64| {
            deviations.partition_point(|&d| d <= limit) as f64 / deviations.len().max(1) as f64
        };
        let (min_gap, max_gap) = (
            gaps.first().copied().unwrap_or(0.0),
            gaps.last().copied().unwrap_or(0.0),
        );
        Self {
            contacts: joints.len(),
            joint,
            min_gap,
            max_gap,
            mean_gap: gaps.iter().sum::<f64>() / gaps.len().max(1) as f64,
            p95_gap: percentile(&gaps, 95),
            p95_deviation: percentile(&deviations, 95),
            max_overlap: (-min_gap).max(0.0),
            overlaps: gaps.iter().filter(|&&g| g < 0.0).count(),
            within_2mm: share(2.0 * mm),
            within_5mm: share(5.0 * mm),
            fit_cuts: 0,
            before_fit: None,
        }
    }
}

/// The `p`-th percentile of sorted values (nearest rank), 0 for none.
fn percentile(sorted: &[f64], p: usize) -> f64 {
    sorted
        .get((sorted.len() * p).div_ceil(100).saturating_sub(1))
        .copied()
        .unwrap_or(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;
    use crate::tiles::{Frame, TileKind};
    use nalgebra::Vector3;

    /// Two quads of 500 mm side by side.
    fn two_quads() -> PolyMesh {
        let grid = generate::grid(2, 1);
        PolyMesh::new(
            grid.positions().iter().map(|p| p * 0.5).collect(),
            grid.faces().to_vec(),
        )
        .unwrap()
    }

    fn tile(x: f64, size: [f64; 3], faces: Vec<usize>) -> Tile {
        let frame = Frame::from_normal(Point3::new(x, 0.25, 0.0), Vector3::z(), &Vector3::x());
        Tile::new(TileKind::Half, faces, frame, size)
    }

    #[test]
    fn tiles_parted_by_a_piece_share_no_joint() {
        // Two quads of 500 mm, a 140 mm tile on each: 360 mm apart.
        let mesh = two_quads();
        let size = [0.14, 0.14, 0.015];
        let mut tiles = vec![tile(0.25, size, vec![0]), tile(0.75, size, vec![1])];
        let found = joints(&mesh, &tiles, 0.01);
        assert_eq!(found.len(), 1);
        assert!((found[0].gap - 0.36).abs() < 1e-9, "{:?}", found);
        // A piece of 340 mm between them, a joint from each: two joints of 10 mm.
        tiles.push(tile(0.5, [0.34, 0.14, 0.015], vec![]));
        let found = joints(&mesh, &tiles, 0.01);
        assert_eq!(
            found.iter().map(|j| j.tiles).collect::<Vec<_>>(),
            [[0, 2], [1, 2]]
        );
        assert!(
            found.iter().all(|j| (j.gap - 0.01).abs() < 1e-9),
            "{found:?}"
        );
    }

    #[test]
    fn tiles_parted_by_pieces_with_a_joint_on_their_middle_share_no_joint() {
        // The same 360 mm tear filled by two pieces of 165 mm, a joint from the tiles and
        // from each other: the joint between the pieces lies on the tiles' middle.
        let mesh = two_quads();
        let size = [0.14, 0.14, 0.015];
        let piece = [0.165, 0.14, 0.015];
        let tiles = vec![
            tile(0.25, size, vec![0]),
            tile(0.75, size, vec![1]),
            tile(0.4125, piece, vec![]),
            tile(0.5875, piece, vec![]),
        ];
        let found = joints(&mesh, &tiles, 0.01);
        assert_eq!(
            found.iter().map(|j| j.tiles).collect::<Vec<_>>(),
            [[0, 2], [1, 3], [2, 3]]
        );
        assert!(
            found.iter().all(|j| (j.gap - 0.01).abs() < 1e-9),
            "{found:?}"
        );
    }

    #[test]
    fn tiles_parted_on_a_curved_surface_share_no_joint_with_each_other() {
        // Tiles 2.4 m apart on a sphere of radius 10 m (a 20 m dome's crown, torn open by
        // the fit), the tear between them filled with pieces on the surface: the chord
        // between the tiles runs 72 mm under the pieces, more than half a tile's width.
        let radius = 10.0;
        let on_sphere = |x: f64, length: f64, faces: Vec<usize>| {
            let angle = x / radius;
            let normal = Vector3::new(angle.sin(), 0.0, angle.cos());
            let origin = Point3::from(normal * radius);
            let along = Vector3::new(angle.cos(), 0.0, -angle.sin());
            let frame = Frame::from_normal(origin, normal, &along);
            Tile::new(TileKind::Full, faces, frame, [length, 0.14, 0.015])
        };
        // Two faces side by side, only their adjacency counts.
        let mesh = generate::grid(2, 1);
        let mut tiles = vec![
            on_sphere(-1.2, 0.28, vec![0]),
            on_sphere(1.2, 0.28, vec![1]),
        ];
        // Pieces of 280 mm at a 290 mm pitch along the arc from one tile to the other.
        let pieces = (1..8).map(|k| on_sphere(-1.2 + 0.29 * k as f64, 0.28, vec![]));
        tiles.extend(pieces);
        let found = joints(&mesh, &tiles, 0.01);
        assert!(
            found.iter().all(|j| j.tiles != [0, 1]),
            "the parted tiles still share a joint: {found:?}"
        );
        assert!(found.iter().all(|j| j.gap < 0.05), "{found:?}");
    }
}
