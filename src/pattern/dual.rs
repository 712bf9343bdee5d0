//! The dual graph of a quad mesh (paper sections 3.2-3.4): faces are nodes, candidate tiles
//! (two quads sharing an edge) are dual edges, and two relations between candidate tiles
//! carry the bond terms of the integer models.

use super::{Bond, Relation};
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
    end_to_end: Vec<[usize; 2]>,
    one_course_apart: Vec<[usize; 2]>,
    /// The relation of each bond with more than one ([`Bond::relations`]), built once.
    herringbone: Vec<[usize; 2]>,
    basket_weave: Vec<[usize; 2]>,
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
        let end_to_end = end_to_end(topology, &edge_tile, &tiles);
        let one_course_apart = one_course_apart(topology, &edge_tile, &tiles);
        let mut graph = Self {
            face_count: mesh.face_count(),
            tiles,
            face_tiles,
            continuous_joints,
            shifted_pairs,
            end_to_end,
            one_course_apart,
            herringbone: Vec::new(),
            basket_weave: Vec::new(),
            regular_vertex_stars,
            star_joints,
        };
        graph.herringbone = graph.union(Bond::Herringbone { weight: 0.0 }.relations());
        graph.basket_weave = graph.union(Bond::BasketWeave { weight: 0.0 }.relations());
        graph
    }

    /// The pairs of one relation.
    pub fn relation(&self, relation: Relation) -> &[[usize; 2]] {
        match relation {
            Relation::ContinuousJoints => &self.continuous_joints,
            Relation::ShiftedPairs => &self.shifted_pairs,
            Relation::EndToEnd => &self.end_to_end,
            Relation::OneCourseApart => &self.one_course_apart,
        }
    }

    /// The pairs of `relations`, each once, in the order of the relations (so the first
    /// relation's pairs keep their indices: the star joints of the continuous joints stay
    /// valid when those come first).
    fn union(&self, relations: &[Relation]) -> Vec<[usize; 2]> {
        let mut seen = std::collections::HashSet::new();
        relations
            .iter()
            .flat_map(|&r| self.relation(r).iter().copied())
            .filter(|&pair| seen.insert(pair))
            .collect()
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

    /// Every face pairs one way only (at most two candidate tiles, one on either side):
    /// the graph of a mesh in level courses (`--courses level`), whose faces pair only along
    /// their course, so that the program's matching part is a set of paths.
    pub fn in_courses(&self) -> bool {
        self.face_tiles.iter().all(|tiles| tiles.len() <= 2)
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

    /// The pairs of candidate tiles that `bond`'s objective scores (the pairs of its
    /// [`Bond::relations`], each once, the first relation's first, at their own indices),
    /// and what each pair of chosen tiles adds to it ([`Bond::pair_weight`]): continuous
    /// joints at `-w` (eq. 2), shifted pairs at `+w` (eq. 3), the herringbone's and the
    /// basket weave's pairs at `-w`, none for the stack bond (eq. 1).
    pub fn bond_pairs(&self, bond: Bond) -> (&[[usize; 2]], f64) {
        let relation: &[[usize; 2]] = match bond.relations() {
            [] => &[],
            [one] => self.relation(*one),
            _ if matches!(bond, Bond::Herringbone { .. }) => &self.herringbone,
            _ => &self.basket_weave,
        };
        (relation, bond.pair_weight())
    }

    /// Pairs of candidate tiles laid end to end along a quad strip: an end face of each
    /// shares the other's end edge, the edge opposite its middle edge.
    pub fn end_to_end(&self) -> &[[usize; 2]] {
        &self.end_to_end
    }

    /// Pairs of parallel candidate tiles aligned one course apart: their middle edges are
    /// two steps apart along a line of edges through regular vertices.
    pub fn one_course_apart(&self) -> &[[usize; 2]] {
        &self.one_course_apart
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

/// The edge of quad `f` opposite its edge `e`.
fn opposite_in_quad(topology: &Topology, f: usize, e: usize) -> Option<usize> {
    let own = topology.face_edges(f);
    if own.len() != 4 {
        return None;
    }
    let i = own.iter().position(|&x| x == e)?;
    Some(own[(i + 2) % 4])
}

/// The pair of tiles `a` and `b`, smaller first, if they share no face.
fn disjoint(tiles: &[CandidateTile], a: usize, b: usize) -> Option<[usize; 2]> {
    let [fa, fb] = [tiles[a].faces, tiles[b].faces];
    (!fa.iter().any(|f| fb.contains(f))).then(|| [a.min(b), a.max(b)])
}

/// End-to-end pairs, found from each tile's end faces: across the end edge (opposite the
/// middle edge) lies a face whose opposite edge is another tile's middle edge.
fn end_to_end(
    topology: &Topology,
    edge_tile: &[Option<usize>],
    tiles: &[CandidateTile],
) -> Vec<[usize; 2]> {
    let mut pairs = Vec::new();
    for (a, tile) in tiles.iter().enumerate() {
        for f in tile.faces {
            let Some(end) = opposite_in_quad(topology, f, tile.middle_edge) else {
                continue;
            };
            let Some(g) = topology.edges()[end].other_face(f) else {
                continue;
            };
            let Some(b) = opposite_in_quad(topology, g, end).and_then(|m| edge_tile[m]) else {
                continue;
            };
            pairs.extend(disjoint(tiles, a, b));
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// Pairs one course apart, found from each tile's middle edge: two steps along the line
/// of edges through each of its ends, where both vertices passed are regular.
fn one_course_apart(
    topology: &Topology,
    edge_tile: &[Option<usize>],
    tiles: &[CandidateTile],
) -> Vec<[usize; 2]> {
    let mut pairs = Vec::new();
    for (a, tile) in tiles.iter().enumerate() {
        let m = tile.middle_edge;
        for v in topology.edges()[m].vertices {
            let Some(next) = topology.opposite_edge(v, m) else {
                continue;
            };
            let [p, q] = topology.edges()[next].vertices;
            let w = if p == v { q } else { p };
            let Some(b) = topology.opposite_edge(w, next).and_then(|e| edge_tile[e]) else {
                continue;
            };
            pairs.extend(disjoint(tiles, a, b));
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}
