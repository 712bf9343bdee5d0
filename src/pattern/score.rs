//! Objective values of a chosen set of tiles, counted directly from the dual graph.

use super::{Bond, DualGraph, Terms};

/// What a pattern scores under eq. (1)-(3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Score {
    /// Chosen tiles (sum of x).
    pub tiles: usize,
    /// Continuous joints among chosen tiles (sum of y at optimum).
    pub continuous_joints: usize,
    /// Shifted pairs among chosen tiles (sum of z at optimum).
    pub shifted_pairs: usize,
    /// Pairs of the bond's relation among chosen tiles ([`DualGraph::bond_pairs`]).
    pub bond_pairs: usize,
    /// The bond's objective value.
    pub objective: f64,
}

/// Scores the tiles marked in `chosen` (indexed like [`DualGraph::tiles`]).
pub fn score(graph: &DualGraph, chosen: &[bool], bond: Bond) -> Score {
    evaluate(graph, chosen, &Terms::uniform(graph, bond))
}

/// Scores the tiles marked in `chosen` under `terms` (one bond, or a bond per zone).
pub(crate) fn evaluate(graph: &DualGraph, chosen: &[bool], terms: &Terms<'_>) -> Score {
    let both = |pairs: &[[usize; 2]]| {
        pairs
            .iter()
            .filter(|[a, b]| chosen[*a] && chosen[*b])
            .count()
    };
    let tiles = chosen.iter().filter(|&&c| c).count();
    let continuous_joints = both(graph.continuous_joints());
    let shifted_pairs = both(graph.shifted_pairs());
    // Eq. (1)-(3): a tile scores one, each pair of the bond's relation what the bond gives it.
    let mut bond_pairs = 0;
    let mut objective = tiles as f64;
    for (_, [a, b], weight) in terms.iter() {
        if chosen[a] && chosen[b] {
            bond_pairs += 1;
            objective += weight;
        }
    }
    Score {
        tiles,
        continuous_joints,
        shifted_pairs,
        bond_pairs,
        objective,
    }
}
