//! Filling the strip between a quad mesh and the surface's edge.
//!
//! A quad mesh rarely reaches the surface's boundary everywhere (the paper notes it; a
//! QuadriFlow mesh covers 67-89 % of the shared example shells). Masons lay cut pieces in
//! the strip left over, continuing the courses. Here the quad lattice is continued past the
//! mesh's boundary, ring by ring: every open edge is extruded outward, in its face's plane,
//! into a square cell, unless that cell would land on a cell already there; each new cell
//! gets a half-tile blank, which is then cut to the surface like any boundary tile. Rings
//! stop where no new cell touches the surface.
//!
//! After the fit stage the tiles no longer sit on their quads (a course may end short of the
//! quad mesh's edge, where its leftover went), so the fill then starts from the tiles
//! themselves: each tile's footprint (its face grown by half a joint, long sides split in
//! two) is a cell, and the footprint's sides on the quad mesh's boundary are the open edges.
//! The pieces are then not kept to their cells but cut to the room the fitted tiles (and the
//! pieces placed before them) leave, a joint from each ([`super::fit::cut_to_room`]): cells
//! continue footprints that the fit moved apart or together, so only the room left gives
//! their joints the joint's width.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};

use super::clip::Point2;
use super::{Frame, SurfaceBoundary, Tile, TileKind};
use crate::mesh::{PolyMesh, Topology};

/// More rings than this would mean the quad mesh covers only a small part of the surface:
/// the pieces would no longer be boundary tiles but a second, unmatched tiling.
const MAX_RINGS: usize = 12;

/// A filler cell and the tile it continues from.
pub(crate) struct Filler {
    /// The half-tile blank placed on the cell (uncut; the caller cuts it to the surface and
    /// to the cell).
    pub tile: Tile,
    /// The cell's corners in the tile's frame, counter-clockwise: without the fit the piece
    /// may not leave it, so that pieces on neighbouring cells do not overlap.
    pub cell: [Point2; 4],
    /// Index into the original tiles of the tile it grew from, or `tiles.len() + k` for the
    /// `k`-th filler.
    pub parent: usize,
}

/// An edge with cells only on its left (seen along `normal`), ready to be extruded.
#[derive(Clone, Copy)]
struct OpenEdge {
    a: Point3<f64>,
    b: Point3<f64>,
    normal: Vector3<f64>,
    parent: usize,
}

/// A placed cell: corners (a convex polygon) and unit normal.
struct Cell {
    corners: Vec<Point3<f64>>,
    normal: Vector3<f64>,
}

impl Cell {
    /// Whether `p` lies over the cell, within half its size of its plane.
    fn covers(&self, p: &Point3<f64>) -> bool {
        let n = self.corners.len();
        let size = (self.corners[n / 2] - self.corners[0]).norm();
        if (p - self.corners[0]).dot(&self.normal).abs() > size / 2.0 {
            return false;
        }
        (0..n).all(|i| {
            (self.corners[(i + 1) % n] - self.corners[i])
                .cross(&(p - self.corners[i]))
                .dot(&self.normal)
                >= 0.0
        })
    }

    fn centroid(&self) -> Point3<f64> {
        Point3::from(
            self.corners.iter().map(|c| c.coords).sum::<Vector3<f64>>() / self.corners.len() as f64,
        )
    }
}

/// The cells placed so far, hashed by centroid.
struct Cells {
    cells: Vec<Cell>,
    grid: HashMap<[i64; 3], Vec<usize>>,
    size: f64,
}

impl Cells {
    fn key(&self, p: &Point3<f64>) -> [i64; 3] {
        [p.x, p.y, p.z].map(|c| (c / self.size).floor() as i64)
    }

    fn add(&mut self, cell: Cell) {
        let key = self.key(&cell.centroid());
        self.grid.entry(key).or_default().push(self.cells.len());
        self.cells.push(cell);
    }

    fn covered(&self, p: &Point3<f64>) -> bool {
        let k = self.key(p);
        (-1..=1)
            .flat_map(|x| {
                (-1..=1).flat_map(move |y| (-1..=1).map(move |z| [k[0] + x, k[1] + y, k[2] + z]))
            })
            .filter_map(|key| self.grid.get(&key))
            .flatten()
            .any(|&c| self.cells[c].covers(p))
    }
}

/// What the fill grows from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Seeds {
    /// The quads: tiles sit on them (the section 3.5 placement).
    Quads,
    /// The tiles' footprints, each grown by half of `joint`: the tiles were moved off their
    /// quads by the fit stage.
    Tiles {
        /// The mortar joint.
        joint: f64,
    },
}

/// Filler cells beyond the boundary of `quads`, each with a half blank of `blank` size
/// (length, width, thickness), kept where they reach onto the surface behind `boundary`.
/// `tiles` are the tiles on the quads (for the fillers' parents); `seeds` says whether the
/// lattice continues from the quads or from the tiles.
pub(crate) fn fill(
    quads: &PolyMesh,
    tiles: &[Tile],
    boundary: &SurfaceBoundary,
    blank: [f64; 3],
    seeds: Seeds,
) -> Vec<Filler> {
    let topology = Topology::new(quads).expect("a PolyMesh is manifold by construction");
    let mut tile_of = vec![usize::MAX; quads.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = t);
    }
    let mut cells = Cells {
        cells: Vec::new(),
        grid: HashMap::new(),
        size: 2.0 * blank[1].max(blank[0]),
    };
    let mut open = Vec::new();
    for (f, &tile) in tile_of.iter().enumerate() {
        let corners: Vec<Point3<f64>> = quads.face_points(f).collect();
        let normal = quads
            .face_area_vector(f)
            .try_normalize(0.0)
            .unwrap_or_else(Vector3::z);
        // Quads without a tile block the fill either way; with tiles as seeds, the tiles'
        // footprints stand for their quads.
        if corners.len() == 4 && (seeds == Seeds::Quads || tile == usize::MAX) {
            cells.add(Cell {
                corners: corners.clone(),
                normal,
            });
        }
        if tile == usize::MAX || seeds != Seeds::Quads {
            continue;
        }
        for (i, &e) in topology.face_edges(f).iter().enumerate() {
            if topology.edges()[e].is_boundary() {
                let n = corners.len();
                open.push(OpenEdge {
                    a: corners[i],
                    b: corners[(i + 1) % n],
                    normal,
                    parent: tile,
                });
            }
        }
    }
    if let Seeds::Tiles { joint } = seeds {
        for (t, tile) in tiles.iter().enumerate() {
            let (corners, open_sides) = footprint(quads, &topology, tile, joint);
            let n = corners.len();
            for (i, open_side) in open_sides.iter().enumerate() {
                if *open_side {
                    open.push(OpenEdge {
                        a: corners[i],
                        b: corners[(i + 1) % n],
                        normal: tile.frame.z,
                        parent: t,
                    });
                }
            }
            cells.add(Cell {
                corners,
                normal: tile.frame.z,
            });
        }
    }

    let mut fillers: Vec<Filler> = Vec::new();
    for _ in 0..MAX_RINGS {
        let mut next = Vec::new();
        for edge in open {
            let along = edge.b - edge.a;
            let Some(outward) = along.cross(&edge.normal).try_normalize(0.0) else {
                continue;
            };
            let depth = along.norm();
            // Cells continue the sheet of their edge: none crosses a crease.
            let Some(sheet) = boundary.sheet_at(&nalgebra::center(&edge.a, &edge.b), depth) else {
                continue;
            };
            // The surface must go on beyond the edge: the middle of the new cell, in the
            // face's plane, lies close to it.
            let middle = nalgebra::center(&edge.a, &edge.b) + outward * (depth / 2.0);
            if boundary.closest_on(&middle, depth / 4.0, sheet).is_none() {
                continue;
            }
            // Continue in the face's plane, then down onto the surface where it curves away
            // (beyond its edge the plane goes on, to be cut off).
            let onto = |q: Point3<f64>| boundary.closest_on(&q, depth, sheet).unwrap_or(q);
            let (a2, b2) = (
                onto(edge.a + outward * depth),
                onto(edge.b + outward * depth),
            );
            // Cells squeezed against the surface's edge by the projection add nothing.
            let area_vector = (edge.a - b2).cross(&(a2 - edge.b)) / 2.0;
            if area_vector.dot(&edge.normal) < 0.3 * depth * depth {
                continue;
            }
            let normal = area_vector.normalize();
            // Counter-clockwise seen along the normal, the open edge traversed backwards.
            let square = [edge.b, edge.a, a2, b2];
            let cell = Cell {
                corners: square.to_vec(),
                normal,
            };
            let centre = cell.centroid();
            // Cells may not overlap beyond a sliver: the centre must be free, and at most two
            // of the probes a fifth of the way in from the corners and edge middles may lie
            // on other cells (on a curved surface neighbouring rows of cells fan in and out).
            let probe = |p: Point3<f64>| p + (centre - p) * 0.2;
            let mids = [0, 1, 2, 3].map(|i| nalgebra::center(&square[i], &square[(i + 1) % 4]));
            let probes = square.iter().chain(&mids).map(|&p| probe(p));
            if cells.covered(&centre) || probes.filter(|p| cells.covered(p)).count() >= 3 {
                continue;
            }
            let frame = Frame::for_corners(&square, normal);
            let tile = Tile::new(TileKind::Half, Vec::new(), frame, blank);
            if matches!(boundary.clip(&tile, 0.0), super::clip::Clipped::Outside) {
                continue;
            }
            let index = tiles.len() + fillers.len();
            for (a, b) in [(edge.a, a2), (a2, b2), (b2, edge.b)] {
                next.push(OpenEdge {
                    a,
                    b,
                    normal,
                    parent: index,
                });
            }
            let local = square.map(|c| {
                let v = tile.frame.to_local(&c);
                [v.x, v.y]
            });
            cells.add(cell);
            fillers.push(Filler {
                tile,
                cell: local,
                parent: edge.parent,
            });
        }
        if next.is_empty() {
            break;
        }
        open = next;
    }
    fillers
}

/// A tile's footprint, its face grown by half a joint, as corners counter-clockwise seen
/// from its `z` (a full tile's long sides split in the middle, so each side of the footprint
/// is about one quad long), and for each side from corner `i` to `i + 1` whether it lies on
/// the quad mesh's boundary: whether the quads of the tile have no neighbour across it.
fn footprint(
    quads: &PolyMesh,
    topology: &Topology,
    tile: &Tile,
    joint: f64,
) -> (Vec<Point3<f64>>, Vec<bool>) {
    use super::fit::contacts::{Side, side_of};
    let (x, y) = (
        tile.size[0] / 2.0 + joint / 2.0,
        tile.size[1] / 2.0 + joint / 2.0,
    );
    let full = tile.faces.len() == 2;
    // Corners, and the side and half (-1: x < 0, 1: x > 0, 0: whole) of each edge.
    let (local, edges): (Vec<[f64; 2]>, Vec<(Side, i8)>) = if full {
        (
            vec![[-x, -y], [0.0, -y], [x, -y], [x, y], [0.0, y], [-x, y]],
            vec![
                (Side::NegY, -1),
                (Side::NegY, 1),
                (Side::PosX, 0),
                (Side::PosY, 1),
                (Side::PosY, -1),
                (Side::NegX, 0),
            ],
        )
    } else {
        (
            vec![[-x, -y], [x, -y], [x, y], [-x, y]],
            vec![
                (Side::NegY, 0),
                (Side::PosX, 0),
                (Side::PosY, 0),
                (Side::NegX, 0),
            ],
        )
    };
    let corners = local
        .iter()
        .map(|p| tile.to_world(Vector3::new(p[0], p[1], 0.0)))
        .collect();
    let mut open = vec![false; edges.len()];
    for (k, &f) in tile.faces.iter().enumerate() {
        // A full tile's first face is its `x < 0` half.
        let half = if full { if k == 0 { -1 } else { 1 } } else { 0 };
        for (i, &e) in topology.face_edges(f).iter().enumerate() {
            if !topology.edges()[e].is_boundary() {
                continue;
            }
            let Some(side) = side_of(quads, topology, tile, f, i) else {
                continue;
            };
            if let Some(slot) = edges
                .iter()
                .position(|&(s, h)| s == side && (h == 0 || h == half))
            {
                open[slot] = true;
            }
        }
    }
    (corners, open)
}
