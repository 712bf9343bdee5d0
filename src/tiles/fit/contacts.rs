//! Which sides of which tiles face each other: the joints the fit makes uniform.
//!
//! Two tiles meet where a mesh edge separates a face of one from a face of the other. Which
//! side of each tile that edge lies on follows from the quad's corners, not from geometry
//! (which the fit changes): a half tile's length axis runs along its face's edges 0-1 and
//! 3-2, so edge 0 is its `-y` side, edge 1 `+x`, edge 2 `+y`, edge 3 `-x`; a full tile's
//! length axis runs from its first face to its second, so going counter-clockwise from the
//! shared edge the first face's edges are `+x` (inside the tile), `+y`, `-x`, `-y` and the
//! second face's `-x` (inside), `-y`, `+x`, `+y`.

use std::collections::BTreeMap;

use nalgebra::Vector3;

use crate::mesh::{PolyMesh, Topology};
use crate::tiles::{Frame, Tile};

/// A side of a tile's rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Side {
    /// The end at `+x` (a head joint for a full tile).
    PosX,
    /// The long side at `+y` (a bed joint).
    PosY,
    /// The end at `-x`.
    NegX,
    /// The long side at `-y`.
    NegY,
}

impl Side {
    /// Sides counter-clockwise from `+x`.
    pub(crate) const CCW: [Side; 4] = [Side::PosX, Side::PosY, Side::NegX, Side::NegY];

    /// The side `k` quarter turns counter-clockwise from this one.
    fn turn(self, k: usize) -> Side {
        let at = Self::CCW.iter().position(|&s| s == self).expect("listed");
        Self::CCW[(at + k) % 4]
    }

    /// Outward unit normal in `frame`.
    pub fn normal(self, frame: &Frame) -> Vector3<f64> {
        match self {
            Side::PosX => frame.x,
            Side::NegX => -frame.x,
            Side::PosY => frame.y,
            Side::NegY => -frame.y,
        }
    }

    /// Distance from the tile's origin to this side, and half the side's length.
    pub fn extents(self, size: &[f64; 3]) -> (f64, f64) {
        let (hx, hy) = (size[0] / 2.0, size[1] / 2.0);
        match self {
            Side::PosX | Side::NegX => (hx, hy),
            Side::PosY | Side::NegY => (hy, hx),
        }
    }

    /// Whether this is a long side (bed joint) rather than an end (head joint).
    pub fn is_long(self) -> bool {
        matches!(self, Side::PosY | Side::NegY)
    }
}

/// Two tiles whose sides face each other across one or more mesh edges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Contact {
    /// The tiles, the smaller index first.
    pub tiles: [usize; 2],
    /// The side of each that faces the other.
    pub sides: [Side; 2],
    /// Mesh edges between them along these sides.
    pub edges: usize,
}

/// The side of `tile` on which the edge from corner `corner` of its face `face` lies.
pub(crate) fn side_of(
    mesh: &PolyMesh,
    topology: &Topology,
    tile: &Tile,
    face: usize,
    corner: usize,
) -> Option<Side> {
    match tile.faces[..] {
        [f] if f == face => Some([Side::NegY, Side::PosX, Side::PosY, Side::NegX][corner % 4]),
        [a, b] => {
            let (own, other, inside) = if face == a {
                (a, b, Side::PosX)
            } else {
                (b, a, Side::NegX)
            };
            let shared = topology
                .face_edges(own)
                .iter()
                .position(|&e| topology.edges()[e].other_face(own) == Some(other))?;
            let n = mesh.faces()[own].len();
            Some(inside.turn((corner + n - shared) % n))
        }
        _ => None,
    }
}

/// Every pair of tiles that meet across mesh edges, with the sides that face each other, in
/// order of the first edge between them.
pub(crate) fn contacts(mesh: &PolyMesh, topology: &Topology, tiles: &[Tile]) -> Vec<Contact> {
    let mut tile_of = vec![usize::MAX; mesh.face_count()];
    for (t, tile) in tiles.iter().enumerate() {
        for &f in &tile.faces {
            tile_of[f] = t;
        }
    }
    // Keyed by tiles and sides; the value is (first edge, count), for a stable order.
    let mut found: BTreeMap<([usize; 2], [Side; 2]), (usize, usize)> = BTreeMap::new();
    for (e, edge) in topology.edges().iter().enumerate() {
        let [f, g] = edge.faces[..] else { continue };
        let (a, b) = (tile_of[f], tile_of[g]);
        if a == usize::MAX || b == usize::MAX || a == b {
            continue;
        }
        let corner = |face: usize| {
            topology
                .face_edges(face)
                .iter()
                .position(|&x| x == e)
                .expect("the face has the edge")
        };
        let (Some(sa), Some(sb)) = (
            side_of(mesh, topology, &tiles[a], f, corner(f)),
            side_of(mesh, topology, &tiles[b], g, corner(g)),
        ) else {
            continue;
        };
        let key = if a < b {
            ([a, b], [sa, sb])
        } else {
            ([b, a], [sb, sa])
        };
        found.entry(key).or_insert((e, 0)).1 += 1;
    }
    let mut list: Vec<(usize, Contact)> = found
        .into_iter()
        .map(|((tiles, sides), (first, edges))| {
            (
                first,
                Contact {
                    tiles,
                    sides,
                    edges,
                },
            )
        })
        .collect();
    list.sort_by_key(|&(first, c)| (first, c.tiles));
    list.into_iter().map(|(_, c)| c).collect()
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::mesh::generate;
    use crate::pattern::Pattern;
    use crate::tiles::{TileSpec, build};

    /// A pattern of `pairs` and `unpaired` faces on a mesh of `faces` faces.
    pub(crate) fn pattern(faces: usize, pairs: Vec<[usize; 2]>, unpaired: Vec<usize>) -> Pattern {
        Pattern {
            faces,
            pairs,
            unpaired,
            excluded: vec![],
            non_quad: vec![],
            continuous_joints: 0,
            shifted_pairs: 0,
            bond_pairs: 0,
            objective: 0.0,
            bound: 0.0,
            gap: 0.0,
            status: crate::pattern::SolveStatus::Optimal,
            bound_source: Default::default(),
            seconds: 0.0,
        }
    }

    #[test]
    fn sides_match_geometry_on_a_grid() {
        // A 4 x 2 grid of unit quads: faces 0..3 in the first row, 4..7 in the second.
        let mesh = generate::grid(4, 2);
        let topology = Topology::new(&mesh).unwrap();
        let spec = TileSpec {
            length: 1.9,
            width: 0.95,
            thickness: 0.1,
            joint: 0.1,
        };
        // Row 0: tiles (0,1) (2,3); row 1 staggered: half 4, tile (5,6), half 7.
        let tiles = build(
            &mesh,
            &pattern(8, vec![[0, 1], [2, 3], [5, 6]], vec![4, 7]),
            &spec,
        )
        .unwrap();
        let found = contacts(&mesh, &topology, &tiles);
        for c in &found {
            // Every side found topologically is the side the neighbour lies beyond.
            let [a, b] = c.tiles.map(|t| &tiles[t]);
            let towards = b.frame.origin - a.frame.origin;
            assert!(c.sides[0].normal(&a.frame).dot(&towards) > 0.0, "{c:?}");
            assert!(c.sides[1].normal(&b.frame).dot(&towards) < 0.0, "{c:?}");
        }
        // Head joint (0,1)|(2,3): one edge, ends facing.
        let head = found.iter().find(|c| c.tiles == [0, 1]).unwrap();
        assert_eq!(head.edges, 1);
        assert!(!head.sides[0].is_long() && !head.sides[1].is_long());
        // Bed joints of (0,1) with half 4 and tile (5,6).
        let bed = found.iter().find(|c| c.tiles == [0, 2]).unwrap();
        assert!(bed.sides[0].is_long() && bed.sides[1].is_long() && bed.edges == 1);
        assert_eq!(found.len(), 7);
    }
}
