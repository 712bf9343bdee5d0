//! The dual graph of a quad mesh (paper sections 3.2-3.4): faces are nodes, candidate tiles
//! (two quads sharing an edge) are dual edges, and two relations between candidate tiles
//! carry the bond terms of the integer models.

use super::Bond;
use crate::mesh::{PolyMesh, Topology};

/// Two adjacent quads that may become one tile. The mesh edge between them is the tile's
/// *middle edge*; the tile's length runs across it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CandidateTile {
    /// The two faces, smaller index first.
    pub faces: [usize; 2],
    /// The mesh edge the two faces share.
    pub middle_edge: usize,
}

/// Candidate tiles of a quad mesh and the relations the paper's models need.
#[derive(Debug, Clone)]
pub struct DualGraph {
    face_count: usize,
    tiles: Vec<CandidateTile>,
    face_tiles: Vec<Vec<usize>>,
    continuous_joints: Vec<[usize; 2]>,
    shifted_pairs: Vec<[usize; 2]>,
    regular_vertex_stars: Vec<[usize; 4]>,
    star_joints: Vec<[usize; 2]>,
}

impl DualGraph {
    /// Builds the dual graph. Faces that are not quads, or are `excluded` (openings, areas
    /// laid by hand), take part in no candidate tile.
    pub fn new(mesh: &PolyMesh, topology: &Topology, excluded: &[bool]) -> Self {
        Self::restricted(mesh, topology, excluded, None)
    }

    /// [`DualGraph::new`] with candidate tiles only across the mesh edges `middle` allows.
    pub fn restricted(
        mesh: &PolyMesh,
        topology: &Topology,
        excluded: &[bool],
        middle: Option<&[bool]>,
    ) -> Self {
        let usable = |f: usize| mesh.is_quad(f) && !excluded.get(f).copied().unwrap_or(false);
        let mut tiles = Vec::new();
        let mut edge_tile = vec![None; topology.edges().len()];
        for (e, edge) in topology.edges().iter().enumerate() {
            if let [a, b] = edge.faces[..] {
                if usable(a) && usable(b) && middle.is_none_or(|m| m[e]) {
                    edge_tile[e] = Some(tiles.len());
                    tiles.push(CandidateTile {
                        faces: [a.min(b), a.max(b)],
                        middle_edge: e,
                    });
                }
            }
        }
        let mut face_tiles = vec![Vec::new(); mesh.face_count()];
        for (t, tile) in tiles.iter().enumerate() {
            for f in tile.faces {
                face_tiles[f].push(t);
            }
        }

        let Joints {
            pairs: continuous_joints,
            stars: regular_vertex_stars,
            star_joints,
        } = continuous_joints(mesh, topology, &edge_tile);
        let shifted_pairs = shifted_pairs(topology, &edge_tile, &tiles);
        Self {
            face_count: mesh.face_count(),
            tiles,
            face_tiles,
            continuous_joints,
            shifted_pairs,
            regular_vertex_stars,
            star_joints,
        }
    }

    /// Number of faces of the mesh (paired or not).
    pub fn face_count(&self) -> usize {
        self.face_count
    }

    /// All candidate tiles, ordered by middle edge.
    pub fn tiles(&self) -> &[CandidateTile] {
        &self.tiles
    }

    /// Candidate tiles that contain face `f` (the paper's E(f)).
    pub fn face_tiles(&self, f: usize) -> &[usize] {
        &self.face_tiles[f]
    }

    /// Pairs of candidate tiles that would form a continuous joint (the paper's y, eq. 2):
    /// their middle edges are opposite edges at an interior valence-4 vertex, so the tiles lie
    /// side by side, aligned, with their end joints on one line.
    pub fn continuous_joints(&self) -> &[[usize; 2]] {
        &self.continuous_joints
    }

    /// Pairs of candidate tiles that lie side by side shifted by one face (the paper's z,
    /// eq. 3, the running bond): a face of one shares a side edge with a face of the other,
    /// and the two middle edges touch opposite ends of that shared edge.
    pub fn shifted_pairs(&self) -> &[[usize; 2]] {
        &self.shifted_pairs
    }

    /// For every interior valence-4 vertex whose four edges are all candidate tiles, those
    /// four tiles in cyclic order `[a, b, c, d]`: `(a, c)` and `(b, d)` are its two
    /// continuous-joint pairs, and at most one of the two pairs fits in a matching.
    pub fn regular_vertex_stars(&self) -> &[[usize; 4]] {
        &self.regular_vertex_stars
    }

    /// For every star of [`DualGraph::regular_vertex_stars`], the indices in
    /// [`DualGraph::continuous_joints`] of its two joints `(a, c)` and `(b, d)`: each joint
    /// belongs to the one vertex where it was found.
    pub fn regular_vertex_star_joints(&self) -> &[[usize; 2]] {
        &self.star_joints
    }

    /// Faces sharing a candidate tile with face `f`.
    pub fn neighbours(&self, f: usize) -> impl Iterator<Item = usize> + '_ {
        self.face_tiles[f].iter().map(move |&t| {
            let [a, b] = self.tiles[t].faces;
            if a == f { b } else { a }
        })
    }

    /// The pairs of candidate tiles that `bond`'s objective scores, and what each pair of
    /// chosen tiles adds to it: continuous joints at `-w` (eq. 2), shifted pairs at `+w`
    /// (eq. 3), none for the stack bond (eq. 1).
    pub fn bond_pairs(&self, bond: Bond) -> (&[[usize; 2]], f64) {
        let relation: &[[usize; 2]] = match bond {
            Bond::Stack => &[],
            Bond::Staggered { .. } => &self.continuous_joints,
            Bond::RunningBond { .. } => &self.shifted_pairs,
        };
        (relation, bond.pair_weight())
    }

    /// The candidate tile made of faces `a` and `b`, if they are adjacent usable quads.
    pub fn tile_between(&self, a: usize, b: usize) -> Option<usize> {
        let key = [a.min(b), a.max(b)];
        self.face_tiles
            .get(a)?
            .iter()
            .copied()
            .find(|&t| self.tiles[t].faces == key)
    }
}

/// What [`continuous_joints`] finds.
struct Joints {
    /// Continuous-joint pairs.
    pairs: Vec<[usize; 2]>,
    /// Full vertex stars.
    stars: Vec<[usize; 4]>,
    /// Indices in `pairs` of each star's two joints.
    star_joints: Vec<[usize; 2]>,
}

/// Continuous-joint pairs and full vertex stars with the indices of their two joints,
/// vertex by vertex in index order.
fn continuous_joints(mesh: &PolyMesh, topology: &Topology, edge_tile: &[Option<usize>]) -> Joints {
    let mut pairs = Vec::new();
    let mut stars = Vec::new();
    let mut star_joints = Vec::new();
    for v in 0..mesh.positions().len() {
        let around = topology.vertex_edges(v);
        let Some(first) = around.first().copied() else {
            continue;
        };
        let Some(opposite) = topology.opposite_edge(v, first) else {
            continue;
        };
        let Some(second) = around
            .iter()
            .copied()
            .find(|&e| e != first && e != opposite)
        else {
            continue;
        };
        let Some(fourth) = topology.opposite_edge(v, second) else {
            continue;
        };
        let cycle = [first, second, opposite, fourth].map(|e| edge_tile[e]);
        for (a, b) in [(cycle[0], cycle[2]), (cycle[1], cycle[3])] {
            if let (Some(a), Some(b)) = (a, b) {
                pairs.push([a.min(b), a.max(b)]);
            }
        }
        if let [Some(a), Some(b), Some(c), Some(d)] = cycle {
            // Both joints were just pushed, (a, c) first.
            stars.push([a, b, c, d]);
            star_joints.push([pairs.len() - 2, pairs.len() - 1]);
        }
    }
    Joints {
        pairs,
        stars,
        star_joints,
    }
}

/// Shifted pairs, found from each interior edge `s = (p, q)` between faces `f` and `g`: the
/// tile through `f`'s edge at `p` and the tile through `g`'s edge at `q` are shifted by one
/// face along `s`, and so are the two tiles the other way round.
fn shifted_pairs(
    topology: &Topology,
    edge_tile: &[Option<usize>],
    tiles: &[CandidateTile],
) -> Vec<[usize; 2]> {
    let mut pairs = Vec::new();
    for (s, edge) in topology.edges().iter().enumerate() {
        let [f, g] = edge.faces[..] else { continue };
        let [p, q] = edge.vertices;
        let tile_at =
            |face: usize, v: usize| topology.face_edge_at(face, s, v).and_then(|e| edge_tile[e]);
        for (a, b) in [
            (tile_at(f, p), tile_at(g, q)),
            (tile_at(f, q), tile_at(g, p)),
        ] {
            let (Some(a), Some(b)) = (a, b) else { continue };
            let [a_faces, b_faces] = [tiles[a].faces, tiles[b].faces];
            if a_faces.iter().any(|x| b_faces.contains(x)) {
                continue;
            }
            pairs.push([a.min(b), a.max(b)]);
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}
