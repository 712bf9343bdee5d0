//! Upper bounds that need no integer solver.

use petgraph::graph::{NodeIndex, UnGraph};

use super::{DualGraph, Terms};

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
            dual.add_edge(
                NodeIndex::new(tile.faces[0]),
                NodeIndex::new(tile.faces[1]),
                t,
            );
        }
    }
    let matching = petgraph::algo::maximum_matching(&dual);
    let mut chosen = vec![false; tiles.len()];
    for (a, b) in matching.edges() {
        let t = graph
            .tile_between(a.index(), b.index())
            .expect("matched faces share a candidate tile");
        chosen[t] = true;
    }
    chosen
}

/// An upper bound on the bond's objective given the largest possible number of tiles.
///
/// Stack and staggered patterns score at most one per tile. In a running bond each chosen
/// tile has four side edges, each shared with at most one other chosen tile, so there are at
/// most two shifted pairs per tile.
/// In zones, every rewarded pair is a shifted pair, at most the largest reward.
pub(super) fn from_tile_count(terms: &Terms<'_>, max_tiles: usize) -> f64 {
    let tiles = max_tiles as f64;
    // Only a reward can raise the objective above the tile count.
    let rewards = terms.iter().filter(|&(_, _, w)| w > 0.0).count();
    tiles + terms.largest_reward() * (2.0 * tiles).min(rewards as f64)
}

/// Most values of the pair count `b` that [`round_down`] tries before it gives up rounding
/// (only a tiny weight needs more).
const MOST_PAIR_COUNTS: usize = 100_000;

/// The largest objective value at most `bound` that a pattern can take.
///
/// Objectives are `step * a - weight * b` (stack, staggered: `b` continuous joints) or
/// `step * a + weight * b` (running bond: `b` shifted pairs) for whole numbers `a >= 0`
/// (tiles, `step` = 1; or in a patch relaxation faces covered, `step` = 1/2) with
/// `step * a <= most`, and `b >= 0`. A solver's bound lies between the optimum and the next
/// value of this form (CBC reports e.g. 96.6 where the optimum 96.5 is proven), so rounding
/// it down to the form keeps it valid and tightens it by up to one step.
///
/// Zones of several weights ([`Terms::common_weight`] `None`) take values `q * k` for a
/// whole `k` when every weight and `step` are whole multiples of a quantum `q`
/// ([`Terms::quantum`]): their bound is rounded down to a multiple of it (else kept).
pub(super) fn round_down(bound: f64, terms: &Terms<'_>, step: f64, most: f64) -> f64 {
    match terms.common_weight() {
        Some(per_pair) => round_down_with(bound, per_pair, step, most),
        None => match terms.quantum(step) {
            Some(q) if bound.is_finite() => {
                let tolerance = 1e-6 + 1e-9 * bound.abs();
                ((bound + tolerance) / q).floor() * q
            }
            _ => bound,
        },
    }
}

/// [`round_down`] for objectives whose every pair adds `per_pair`.
fn round_down_with(bound: f64, per_pair: f64, step: f64, most: f64) -> f64 {
    let (weight, reward) = (per_pair.abs(), per_pair > 0.0);
    if !bound.is_finite() {
        return bound;
    }
    // Room for the solver's tolerances, which can leave its bound a hair below the optimum.
    let tolerance = 1e-6 + 1e-9 * bound.abs();
    let largest_a = (most / step + 1e-9).floor();
    let mut best = f64::NEG_INFINITY;
    for b in 0..=MOST_PAIR_COUNTS {
        let term = if reward {
            weight * b as f64
        } else {
            -weight * b as f64
        };
        // No larger b can do better: a penalty only lowers what the tiles reach, and a
        // reward beyond the bound leaves no room for them.
        let exhausted = if reward {
            term > bound + tolerance
        } else {
            largest_a * step + term < best
        };
        if exhausted || (b > 0 && weight == 0.0) {
            return best;
        }
        let a = ((bound + tolerance - term) / step).floor().min(largest_a);
        if a >= 0.0 {
            best = best.max(a * step + term);
        }
    }
    bound
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_round_down_to_values_a_pattern_can_take() {
        let staggered = |weight: f64| -weight;
        // Half steps: 96.6 cannot be reached, 96.5 can.
        assert_eq!(round_down_with(96.6, staggered(0.5), 1.0, 100.0), 96.5);
        assert_eq!(round_down_with(96.5, staggered(0.5), 1.0, 100.0), 96.5);
        assert_eq!(
            round_down_with(96.4999999, staggered(0.5), 1.0, 100.0),
            96.5
        );
        // w = 0.3 and at most 97 tiles: 97 - 0.3 = 96.7 is too much, 97 - 0.6 = 96.4 fits; with
        // 99 tiles allowed, 99 - 8 * 0.3 = 96.6 is reached exactly.
        assert!((round_down_with(96.6, staggered(0.3), 1.0, 97.0) - 96.4).abs() < 1e-9);
        assert!((round_down_with(96.6, staggered(0.3), 1.0, 100.0) - 96.6).abs() < 1e-9);
        // More tiles than `most` are impossible.
        assert_eq!(round_down_with(120.2, staggered(0.5), 1.0, 100.0), 100.0);
        assert_eq!(round_down_with(96.7, 0.0, 1.0, 100.0), 96.0);
        // Patch relaxations count half a tile per face.
        assert_eq!(round_down_with(10.4, staggered(0.5), 0.5, 12.0), 10.0);
        assert!((round_down_with(10.4, staggered(0.7), 0.5, 12.0) - 10.3).abs() < 1e-9);
        // Running bond: tiles plus w per shifted pair; 8 + 8 * 0.3 = 10.4 is reached exactly.
        let running = |weight: f64| weight;
        assert_eq!(round_down_with(10.4, running(0.5), 1.0, 12.0), 10.0);
        assert!((round_down_with(10.45, running(0.3), 1.0, 12.0) - 10.4).abs() < 1e-9);
        assert_eq!(round_down_with(0.4, running(0.5), 1.0, 12.0), 0.0);
        assert_eq!(
            round_down_with(f64::INFINITY, staggered(0.5), 1.0, 12.0),
            f64::INFINITY
        );
    }
}
