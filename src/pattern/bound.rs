//! Upper bounds that need no integer solver.

use petgraph::graph::{NodeIndex, UnGraph};

use super::{Bond, DualGraph};

/// A maximum-cardinality matching (Edmonds' blossom algorithm, via `petgraph`) of the faces
/// not blocked by `fixed` tiles, using only `free` tiles. Returned as chosen free tiles.
pub(super) fn maximum_matching(graph: &DualGraph, free: &[bool], fixed: &[bool]) -> Vec<bool> {
    let tiles = graph.tiles();
    let mut blocked = vec![false; graph.face_count()];
    for (t, _) in fixed.iter().enumerate().filter(|(_, on)| **on) {
        tiles[t].faces.iter().for_each(|&f| blocked[f] = true);
    }
    let mut dual: UnGraph<(), usize> = UnGraph::with_capacity(graph.face_count(), tiles.len());
    for _ in 0..graph.face_count() {
        dual.add_node(());
    }
    for (t, tile) in tiles.iter().enumerate() {
        if free[t] && !tile.faces.iter().any(|&f| blocked[f]) {
            dual.add_edge(NodeIndex::new(tile.faces[0]), NodeIndex::new(tile.faces[1]), t);
        }
    }
    let matching = petgraph::algo::maximum_matching(&dual);
    let mut chosen = vec![false; tiles.len()];
    for (a, b) in matching.edges() {
        let t = graph.tile_between(a.index(), b.index()).expect("matched faces share a candidate tile");
        chosen[t] = true;
    }
    chosen
}

/// An upper bound on the bond's objective given the largest possible number of tiles.
///
/// Stack and staggered patterns score at most one per tile. In a running bond each chosen
/// tile has four side edges, each shared with at most one other chosen tile, so there are at
/// most two shifted pairs per tile.
pub(super) fn from_tile_count(graph: &DualGraph, bond: Bond, max_tiles: usize) -> f64 {
    let tiles = max_tiles as f64;
    match bond {
        Bond::Stack | Bond::Staggered { .. } => tiles,
        Bond::RunningBond { weight } => tiles + weight * (2.0 * tiles).min(graph.shifted_pairs().len() as f64),
    }
}
