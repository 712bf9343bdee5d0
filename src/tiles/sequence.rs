//! Laying order: the sequence in which a mason (or a robot) places the tiles of a vault.
//!
//! Thin-tile vaults are built without full formwork, course by course from the supports,
//! each tile held by the mortar of tiles already laid. The order here grows from the support
//! tiles and always lays next the lowest tile that touches one already laid, so courses rise
//! evenly from every support.

use std::cmp::Reverse;
use std::collections::{BTreeSet, BinaryHeap};

use nalgebra::{Point3, Vector3};
use serde::Serialize;

use super::{Tile, outline};
use crate::geom::{HashGrid, closest};
use crate::mesh::{PolyMesh, Topology};

/// Where the vault stands.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SequenceOptions {
    /// The up direction (gravity points the other way); default `+z`.
    pub up: Vector3<f64>,
    /// Tiles with a boundary edge within this height of the lowest boundary point stand on
    /// the supports; model units.
    pub support_band: f64,
}

/// The laying order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Sequence {
    /// Tiles that stand on a support.
    pub support_tiles: usize,
    /// Tiles that, at their step, touch no laid tile lower than themselves and stand on no
    /// support: they need a prop.
    pub unsupported: usize,
    /// What the vault stands on.
    pub support: Support,
    /// Whole tiles (uncut, longer than wide) on slopes steeper than [`SLOPE_DEGREES`].
    pub sloped_tiles: usize,
    /// Of [`Self::sloped_tiles`], those whose length runs up the slope (within 45 degrees of
    /// it) rather than along the level: a course of them climbs. Level courses
    /// ([`crate::pattern::Courses::Level`]) keep this near zero only where one family of the
    /// quad rows is level (barrels, webs); on shells curved both ways, where rows turn, a
    /// region's courses are level on one side and climb on another (docs/journal.md, *Level courses
    /// are not level everywhere*).
    pub climbing_tiles: usize,
}

/// Slope (degrees from level) beyond which whole tiles are counted as lying level or
/// climbing ([`Sequence::climbing_tiles`]).
pub const SLOPE_DEGREES: f64 = 20.0;

/// What the tiles are laid from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// The lowest stretch of the boundary (within the support band): a vault on its supports.
    Edges,
    /// Nothing: the mesh has no boundary (a closed surface), so no tile stands on a support
    /// and the order starts at the lowest tile.
    NoBoundary,
    /// The ground: the surface is level (its height varies by less than the support band), so
    /// every tile lies on the formwork or floor and none needs a prop.
    Level,
}

/// Numbers every tile's `step` (0 first) and summarises the order. Tiles touch when their
/// faces share a mesh edge, or when `links` pairs them (filler pieces and their parents).
pub fn laying_order(
    mesh: &PolyMesh,
    tiles: &mut [Tile],
    links: &[[usize; 2]],
    options: &SequenceOptions,
) -> Sequence {
    let topology = Topology::new(mesh).expect("a PolyMesh is manifold by construction");
    let up = options.up.try_normalize(0.0).unwrap_or_else(Vector3::z);
    let height = |p: &nalgebra::Point3<f64>| p.coords.dot(&up);
    let mut tile_of = vec![None; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = Some(t));
    }
    let mut neighbours: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); tiles.len()];
    let mut boundary_low = vec![f64::INFINITY; tiles.len()];
    // The mesh's lowest boundary point, whether or not a tile holds the face there (the
    // lowest quads may be unpaired, or left out as off the surface).
    let mut lowest = f64::INFINITY;
    for edge in topology.edges() {
        match edge.faces[..] {
            [f, g] => {
                if let (Some(a), Some(b)) = (tile_of[f], tile_of[g])
                    && a != b
                {
                    neighbours[a].insert(b);
                    neighbours[b].insert(a);
                }
            }
            [f] => {
                let low = edge
                    .vertices
                    .iter()
                    .map(|&v| height(&mesh.positions()[v]))
                    .fold(f64::INFINITY, f64::min);
                lowest = lowest.min(low);
                if let Some(a) = tile_of[f] {
                    boundary_low[a] = boundary_low[a].min(low);
                }
            }
            _ => {}
        }
    }
    for &[a, b] in links {
        neighbours[a].insert(b);
        neighbours[b].insert(a);
    }
    let (low, high) = mesh
        .positions()
        .iter()
        .map(height)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
            (lo.min(h), hi.max(h))
        });
    let support = if high - low <= options.support_band {
        Support::Level
    } else if lowest.is_finite() {
        Support::Edges
    } else {
        Support::NoBoundary
    };
    // Pieces beyond the quad mesh (no faces) stand on a support when they sit low enough.
    let width = tiles.iter().map(|t| t.size[1]).fold(0.0, f64::max);
    let low_boundary = LowBoundary::new(
        mesh,
        &topology,
        &height,
        lowest + options.support_band,
        width,
    );
    let on_support: Vec<bool> = tiles
        .iter()
        .zip(&boundary_low)
        .map(|(t, &h)| match support {
            Support::Level => true,
            Support::NoBoundary => false,
            Support::Edges => {
                let h = if t.faces.is_empty() {
                    height(&t.frame.origin)
                } else {
                    h
                };
                h <= lowest + options.support_band || low_boundary.holds(t, &height)
            }
        })
        .collect();
    // Rank of each tile by height, lowest first (ties by index): the frontier's key.
    let mut by_height: Vec<usize> = (0..tiles.len()).collect();
    by_height.sort_by(|&a, &b| {
        height(&tiles[a].frame.origin)
            .total_cmp(&height(&tiles[b].frame.origin))
            .then(a.cmp(&b))
    });
    let mut level = vec![0; tiles.len()];
    by_height
        .iter()
        .enumerate()
        .for_each(|(rank, &t)| level[t] = rank);

    let mut laid = vec![false; tiles.len()];
    let mut queued = vec![false; tiles.len()];
    let mut frontier = BinaryHeap::new();
    for t in (0..tiles.len()).filter(|&t| on_support[t]) {
        queued[t] = true;
        frontier.push(Reverse((level[t], t)));
    }
    let (mut step, mut unsupported) = (0, 0);
    while step < tiles.len() {
        let Some(Reverse((_, t))) = frontier.pop() else {
            // A part that touches neither support nor laid tiles: start it at its lowest tile.
            let t = by_height
                .iter()
                .copied()
                .find(|&t| !laid[t])
                .expect("tiles remain");
            queued[t] = true;
            frontier.push(Reverse((level[t], t)));
            continue;
        };
        let rests = on_support[t]
            || neighbours[t]
                .iter()
                .any(|&n| laid[n] && level[n] < level[t]);
        unsupported += usize::from(!rests);
        laid[t] = true;
        tiles[t].step = step;
        step += 1;
        for &n in &neighbours[t] {
            if !queued[n] {
                queued[n] = true;
                frontier.push(Reverse((level[n], n)));
            }
        }
    }
    let (sloped_tiles, climbing_tiles) = climbing(tiles, &up);
    Sequence {
        support_tiles: on_support.iter().filter(|&&s| s).count(),
        unsupported,
        support,
        sloped_tiles,
        climbing_tiles,
    }
}

/// The quad mesh's boundary edges within the support band: where a vault stands.
struct LowBoundary {
    top: f64,
    edges: Vec<[Vector3<f64>; 2]>,
    grid: HashGrid,
}

impl LowBoundary {
    /// The boundary edges of `mesh` with an end no higher than `top`, found by cells of side
    /// `cell` (a tile's width).
    fn new(
        mesh: &PolyMesh,
        topology: &Topology,
        height: &dyn Fn(&Point3<f64>) -> f64,
        top: f64,
        cell: f64,
    ) -> Self {
        let at = |v: usize| mesh.positions()[v];
        let edges: Vec<[Point3<f64>; 2]> = topology
            .edges()
            .iter()
            .filter(|e| e.is_boundary() && e.vertices.iter().any(|&v| height(&at(v)) <= top))
            .map(|e| e.vertices.map(at))
            .collect();
        let grid = HashGrid::of_points(cell, &edges);
        let edges = edges.iter().map(|e| e.map(|p| p.coords)).collect();
        Self { top, edges, grid }
    }

    /// Whether `tile` stands on this stretch of boundary though its quads hold none of it
    /// (the boundary's own quads unpaired, cut away or left out as off the surface, as at
    /// the low corners of a tight saddle): a corner of its solid within the band and within
    /// a quarter of its width of a low boundary edge (the next course's corners are a
    /// course's pitch from it).
    fn holds(&self, tile: &Tile, height: &dyn Fn(&Point3<f64>) -> f64) -> bool {
        let reach = tile.size[1] / 4.0;
        outline::world_corners(tile).iter().any(|c| {
            height(c) <= self.top
                && self.grid.near(c, reach).iter().any(|&k| {
                    let [a, b] = &self.edges[k];
                    (closest::on_segment(&c.coords, a, b) - c.coords).norm() <= reach
                })
        })
    }
}

/// Whole tiles (uncut, at least half as long again as wide) on slopes steeper than
/// [`SLOPE_DEGREES`] with respect to `up` (a unit vector), and how many of them run up the
/// slope: their length within 45 degrees of the slope's direction in their plane.
fn climbing(tiles: &[Tile], up: &Vector3<f64>) -> (usize, usize) {
    let (mut sloped, mut climbs) = (0, 0);
    for tile in tiles {
        if tile.cut.is_some() || tile.size[0] < 1.5 * tile.size[1] {
            continue;
        }
        let normal = tile.frame.z;
        let slope = up - normal * normal.dot(up);
        if slope.norm() < SLOPE_DEGREES.to_radians().sin() {
            continue;
        }
        sloped += 1;
        if tile.frame.x.dot(&slope).abs() > slope.norm() * std::f64::consts::FRAC_1_SQRT_2 {
            climbs += 1;
        }
    }
    (sloped, climbs)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::generate;
    use crate::tiles::{Frame, TileKind};

    /// A tile (or, without faces, a filler piece) lying flat at `(x, y)` of the plane z = 0.
    fn tile_at(faces: Vec<usize>, x: f64, y: f64) -> Tile {
        let frame = Frame {
            origin: Point3::new(x, y, 0.0),
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        };
        Tile::new(TileKind::Full, faces, frame, [1.9, 0.9, 0.1])
    }

    #[test]
    fn a_mesh_whose_boundary_quads_hold_no_tile_still_stands_on_its_boundary() {
        // A 4 x 4 wall of unit quads standing in the plane z = 0 with y up; the two tiles
        // cover the four inner quads only, so no tile holds a boundary face (its quads
        // unpaired or left out as off the surface), and a filler piece lies at the foot.
        let mesh = generate::grid(4, 4);
        let face_at = |x: f64, y: f64| {
            (0..mesh.face_count())
                .find(|&f| {
                    let c = mesh.face_centroid(f);
                    (c.x - x).abs() < 0.1 && (c.y - y).abs() < 0.1
                })
                .unwrap()
        };
        let mut tiles = vec![
            tile_at(vec![face_at(1.5, 1.5), face_at(2.5, 1.5)], 2.0, 1.5),
            tile_at(vec![face_at(1.5, 2.5), face_at(2.5, 2.5)], 2.0, 2.5),
            tile_at(vec![], 2.0, 0.2),
        ];
        let options = SequenceOptions {
            up: Vector3::y(),
            support_band: 0.5,
        };
        let order = laying_order(&mesh, &mut tiles, &[[0, 2]], &options);
        // It has a boundary: the laying order must not say it has none.
        assert_eq!(order.support, Support::Edges);
        // The piece at the foot stands on the support; the tiles rest on it and each other.
        assert_eq!(order.support_tiles, 1);
        assert_eq!(order.unsupported, 0);
        assert_eq!(tiles[2].step, 0);
        // A standing wall: its whole tiles lie along the level (x), none climbs.
        assert_eq!((order.sloped_tiles, order.climbing_tiles), (3, 0));
    }

    #[test]
    fn a_tile_reaching_down_to_the_low_boundary_stands_on_it() {
        // The 4 x 4 wall again, y up: one tile on two quads of the second row, none on the
        // boundary's quads (the low corners of a tight saddle leave them unpaired or cut
        // away). Placed on its quads it floats (a prop); where its solid comes down to the
        // foot (its lower corners 0.15 up: within the band and a quarter of its width of the
        // boundary) it stands there, but not with them 0.3 up, as far as the next course.
        let mesh = generate::grid(4, 4);
        let faces: Vec<usize> = (0..mesh.face_count())
            .filter(|&f| {
                let c = mesh.face_centroid(f);
                (c.y - 1.5).abs() < 0.1 && (c.x - 2.0).abs() < 1.0
            })
            .collect();
        let options = SequenceOptions {
            up: Vector3::y(),
            support_band: 0.5,
        };
        for (y, supports) in [(1.5, 0), (0.75, 0), (0.6, 1)] {
            let mut tiles = vec![tile_at(faces.clone(), 2.0, y)];
            let order = laying_order(&mesh, &mut tiles, &[], &options);
            assert_eq!(order.support, Support::Edges);
            assert_eq!(order.support_tiles, supports, "{y}");
            assert_eq!(order.unsupported, 1 - supports, "{y}");
        }
    }

    #[test]
    fn tiles_running_up_a_slope_are_told_from_level_ones() {
        // A roof plane rising 30 degrees along y: a tile along x lies level, one along the
        // fall line climbs, one turned 30 degrees off level still lies level, a half tile and
        // a tile on a level floor are not counted.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let normal = Vector3::new(0.0, -s, c);
        let up_roof = Vector3::new(0.0, c, s);
        let on_roof = |along: Vector3<f64>, size: [f64; 3]| {
            let x = along.normalize();
            let frame = Frame {
                origin: Point3::origin(),
                x,
                y: normal.cross(&x),
                z: normal,
            };
            Tile::new(TileKind::Full, Vec::new(), frame, size)
        };
        let whole = [0.28, 0.14, 0.015];
        let tiles = vec![
            on_roof(Vector3::x(), whole),
            on_roof(up_roof, whole),
            on_roof(
                Vector3::x() * 30f64.to_radians().cos() + up_roof * 30f64.to_radians().sin(),
                whole,
            ),
            on_roof(up_roof, [0.14, 0.14, 0.015]),
            tile_at(Vec::new(), 5.0, 5.0),
        ];
        assert_eq!(climbing(&tiles, &Vector3::z()), (3, 1));
    }
}
