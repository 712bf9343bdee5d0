//! Filling the strip between a quad mesh and the surface's edge.
//!
//! A quad mesh rarely reaches the surface's boundary everywhere (the paper notes it; a
//! QuadriFlow mesh covers 67-89 % of the shared example shells). Masons lay cut pieces in
//! the strip left over, continuing the courses. Here the quad lattice is continued past the
//! mesh's boundary, ring by ring: every open edge is extruded outward, in its face's plane,
//! into a square cell, unless that cell would land on a cell already there; each new cell
//! gets a half-tile blank, which is then cut to the surface like any boundary tile. Rings
//! stop where no new cell touches the surface.

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
    /// The cell's corners in the tile's frame, counter-clockwise: the piece may not leave it,
    /// so that pieces on neighbouring cells do not overlap.
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

/// A placed cell: corners and unit normal.
struct Cell {
    corners: [Point3<f64>; 4],
    normal: Vector3<f64>,
}

impl Cell {
    /// Whether `p` lies over the cell, within half its size of its plane.
    fn covers(&self, p: &Point3<f64>) -> bool {
        let size = (self.corners[2] - self.corners[0]).norm();
        if (p - self.corners[0]).dot(&self.normal).abs() > size / 2.0 {
            return false;
        }
        (0..4).all(|i| (self.corners[(i + 1) % 4] - self.corners[i]).cross(&(p - self.corners[i])).dot(&self.normal) >= 0.0)
    }

    fn centroid(&self) -> Point3<f64> {
        Point3::from(self.corners.iter().map(|c| c.coords).sum::<Vector3<f64>>() / 4.0)
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
            .flat_map(|x| (-1..=1).flat_map(move |y| (-1..=1).map(move |z| [k[0] + x, k[1] + y, k[2] + z])))
            .filter_map(|key| self.grid.get(&key))
            .flatten()
            .any(|&c| self.cells[c].covers(p))
    }
}

/// Filler cells beyond the boundary of `quads`, each with a half blank of `blank` size
/// (length, width, thickness), kept where they reach onto the surface behind `boundary`.
/// `tiles` are the tiles on the quads (for the fillers' parents).
pub(crate) fn fill(quads: &PolyMesh, tiles: &[Tile], boundary: &SurfaceBoundary, blank: [f64; 3]) -> Vec<Filler> {
    let topology = Topology::new(quads).expect("a PolyMesh is manifold by construction");
    let mut tile_of = vec![usize::MAX; quads.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        tile.faces.iter().for_each(|&f| tile_of[f] = t);
    }
    let mut cells = Cells { cells: Vec::new(), grid: HashMap::new(), size: 2.0 * blank[1].max(blank[0]) };
    let mut open = Vec::new();
    for f in 0..quads.face_count() {
        let corners: Vec<Point3<f64>> = quads.face_points(f).collect();
        let normal = quads.face_area_vector(f).try_normalize(0.0).unwrap_or_else(Vector3::z);
        if let [a, b, c, d] = corners[..] {
            cells.add(Cell { corners: [a, b, c, d], normal });
        }
        if tile_of[f] == usize::MAX {
            continue;
        }
        for (i, &e) in topology.face_edges(f).iter().enumerate() {
            if topology.edges()[e].is_boundary() {
                let n = corners.len();
                open.push(OpenEdge { a: corners[i], b: corners[(i + 1) % n], normal, parent: tile_of[f] });
            }
        }
    }

    let mut fillers: Vec<Filler> = Vec::new();
    for _ in 0..MAX_RINGS {
        let mut next = Vec::new();
        for edge in open {
            let along = edge.b - edge.a;
            let Some(outward) = along.cross(&edge.normal).try_normalize(0.0) else { continue };
            let depth = along.norm();
            // The surface must go on beyond the edge: the middle of the new cell, in the
            // face's plane, lies close to it.
            let middle = nalgebra::center(&edge.a, &edge.b) + outward * (depth / 2.0);
            if boundary.closest(&middle, depth / 4.0).is_none() {
                continue;
            }
            // Continue in the face's plane, then down onto the surface where it curves away
            // (beyond its edge the plane goes on, to be cut off).
            let onto = |q: Point3<f64>| boundary.closest(&q, depth).unwrap_or(q);
            let (a2, b2) = (onto(edge.a + outward * depth), onto(edge.b + outward * depth));
            // Cells squeezed against the surface's edge by the projection add nothing.
            let area_vector = (edge.a - b2).cross(&(a2 - edge.b)) / 2.0;
            if area_vector.dot(&edge.normal) < 0.3 * depth * depth {
                continue;
            }
            let normal = area_vector.normalize();
            // Counter-clockwise seen along the normal, the open edge traversed backwards.
            let cell = Cell { corners: [edge.b, edge.a, a2, b2], normal };
            let centre = cell.centroid();
            // Cells may not overlap beyond a sliver: the centre must be free, and at most two
            // of the probes a fifth of the way in from the corners and edge middles may lie
            // on other cells (on a curved surface neighbouring rows of cells fan in and out).
            let probe = |p: Point3<f64>| p + (centre - p) * 0.2;
            let mids = [0, 1, 2, 3].map(|i| nalgebra::center(&cell.corners[i], &cell.corners[(i + 1) % 4]));
            let probes = cell.corners.iter().chain(&mids).map(|&p| probe(p));
            if cells.covered(&centre) || probes.filter(|p| cells.covered(p)).count() >= 3 {
                continue;
            }
            let frame = Frame::for_corners(&cell.corners, normal);
            let tile = Tile::new(TileKind::Half, Vec::new(), frame, blank);
            if matches!(boundary.clip(&tile, 0.0), super::clip::Clipped::Outside) {
                continue;
            }
            let index = tiles.len() + fillers.len();
            for (a, b) in [(edge.a, a2), (a2, b2), (b2, edge.b)] {
                next.push(OpenEdge { a, b, normal, parent: index });
            }
            let local = cell.corners.map(|c| {
                let v = tile.frame.to_local(&c);
                [v.x, v.y]
            });
            cells.add(cell);
            fillers.push(Filler { tile, cell: local, parent: edge.parent });
        }
        if next.is_empty() {
            break;
        }
        open = next;
    }
    fillers
}
