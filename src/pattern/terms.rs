//! The bond terms of one solve (paper section 3.4): which pairs of candidate tiles the
//! objective scores and what each adds when both its tiles are chosen. Built once per solve
//! from the bond, or from a bond per face ([`super::PatternOptions::zones`]); the score, the
//! program, the bounds and every heuristic read the objective from here.

use std::borrow::Cow;
use std::collections::HashMap;

use super::{Bond, DualGraph, Relation};

/// The relations in the order zoned terms list them: the continuous joints first, so that
/// the compact joint form can find them ([`Terms::joint_term`]).
const RELATIONS: [Relation; 4] = [
    Relation::ContinuousJoints,
    Relation::ShiftedPairs,
    Relation::EndToEnd,
    Relation::OneCourseApart,
];

/// The objective of eqs. (1)-(3) beyond one per tile: scored pairs and their weights.
#[derive(Debug, Clone)]
pub(crate) struct Terms<'g> {
    pairs: Cow<'g, [[usize; 2]]>,
    weights: Weights,
    /// For each continuous joint of the graph ([`DualGraph::continuous_joints`]), its index
    /// among `pairs` when the terms score it.
    joints: Joints,
}

#[derive(Debug, Clone)]
enum Weights {
    /// Every pair adds the same (one bond).
    Uniform(f64),
    /// A weight per pair (zones), none zero, and the distinct weights among them (a few:
    /// each bond's in quarters), which the bounds ask about on every patch.
    PerPair(Vec<f64>, Vec<f64>),
}

#[derive(Debug, Clone)]
enum Joints {
    /// Continuous joint `i` is pair `i` (a bond whose first relation is the joints).
    Leading(usize),
    /// Joint `i` is pair `map[i]`, if scored.
    Map(Vec<Option<usize>>),
}

impl<'g> Terms<'g> {
    /// The terms of one bond on every face: the pairs of [`Bond::relations`] at
    /// [`Bond::pair_weight`] (see [`DualGraph::bond_pairs`]).
    pub fn uniform(graph: &'g DualGraph, bond: Bond) -> Self {
        let (pairs, weight) = graph.bond_pairs(bond);
        let leading = if bond.relations().first() == Some(&Relation::ContinuousJoints) {
            graph.continuous_joints().len()
        } else {
            0
        };
        Self {
            pairs: Cow::Borrowed(pairs),
            weights: Weights::Uniform(weight),
            joints: Joints::Leading(leading),
        }
    }

    /// The terms of a bond per face (`zones`, indexed by face). Each face of a pair's two
    /// tiles carries a quarter of the pair: a pair of a relation of a face's bond counts, at
    /// that bond's [`Bond::pair_weight`], for each of its four faces in that bond. A pair
    /// inside one zone so scores as that zone's bond scores it (a pair in several of its
    /// relations once); a pair across a zone border as each zone would, in proportion to its
    /// faces in each, so that the tiles along a border follow both bonds.
    pub fn zoned(graph: &DualGraph, zones: &[Bond]) -> Terms<'static> {
        let tiles = graph.tiles();
        // Every pair of any relation, once, with the relations it is in.
        let mut index: HashMap<[usize; 2], usize> = HashMap::new();
        let mut found: Vec<([usize; 2], Vec<Relation>)> = Vec::new();
        let mut joint_pair = vec![0; graph.continuous_joints().len()];
        for relation in RELATIONS {
            for (i, &pair) in graph.relation(relation).iter().enumerate() {
                let k = *index.entry(pair).or_insert_with(|| {
                    found.push((pair, Vec::new()));
                    found.len() - 1
                });
                found[k].1.push(relation);
                if relation == Relation::ContinuousJoints {
                    joint_pair[i] = k;
                }
            }
        }
        let mut pairs = Vec::new();
        let mut weights = Vec::new();
        let mut term_of = vec![None; found.len()];
        for (k, ([a, b], relations)) in found.into_iter().enumerate() {
            let weight: f64 = tiles[a]
                .faces
                .iter()
                .chain(&tiles[b].faces)
                .map(|&f| zones[f])
                .filter(|bond| relations.iter().any(|r| bond.relations().contains(r)))
                .map(|bond| bond.pair_weight() / 4.0)
                .sum();
            if weight != 0.0 {
                term_of[k] = Some(pairs.len());
                pairs.push([a, b]);
                weights.push(weight);
            }
        }
        let mut distinct = weights.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        Terms {
            pairs: Cow::Owned(pairs),
            weights: Weights::PerPair(weights, distinct),
            joints: Joints::Map(joint_pair.iter().map(|&k| term_of[k]).collect()),
        }
    }

    /// The scored pairs of candidate tiles.
    pub fn pairs(&self) -> &[[usize; 2]] {
        &self.pairs
    }

    /// What pair `i` adds when both its tiles are chosen: `-w` for a penalty (eq. 2, the
    /// herringbone's and basket weave's pairs), `+w` for a reward (eq. 3).
    pub fn weight(&self, i: usize) -> f64 {
        match &self.weights {
            Weights::Uniform(weight) => *weight,
            Weights::PerPair(weights, _) => weights[i],
        }
    }

    /// The pairs with their index and weight.
    pub fn iter(&self) -> impl Iterator<Item = (usize, [usize; 2], f64)> + '_ {
        self.pairs
            .iter()
            .enumerate()
            .map(|(i, &pair)| (i, pair, self.weight(i)))
    }

    /// True when nothing but tiles counts (the stack bond, eq. 1, on every face).
    pub fn is_empty(&self) -> bool {
        match &self.weights {
            Weights::Uniform(weight) => *weight == 0.0 || self.pairs.is_empty(),
            Weights::PerPair(weights, _) => weights.is_empty(),
        }
    }

    /// The one weight of every scored pair, if they share one (zero when none is scored):
    /// then objectives take the values [`super::bound::round_down`] knows.
    pub fn common_weight(&self) -> Option<f64> {
        match self.distinct() {
            [] => Some(0.0),
            [one] => Some(*one),
            _ => None,
        }
    }

    /// The largest `q` (a whole fraction of the smallest weight, down to a 64th) of which
    /// every weight and `step` are whole multiples: then every objective is one too.
    pub fn quantum(&self, step: f64) -> Option<f64> {
        let whole = |x: f64, q: f64| ((x / q).round() * q - x).abs() <= 1e-12 * x.abs().max(1.0);
        let distinct = self.distinct();
        let smallest = distinct.iter().map(|w| w.abs()).fold(step, f64::min);
        (1..=64)
            .map(|n| smallest / n as f64)
            .find(|&q| whole(step, q) && distinct.iter().all(|&w| whole(w, q)))
    }

    /// The largest reward of one pair (zero when no pair is a reward).
    pub fn largest_reward(&self) -> f64 {
        self.distinct().iter().copied().fold(0.0, f64::max)
    }

    /// The distinct weights of the scored pairs (one bond: its weight).
    fn distinct(&self) -> &[f64] {
        match &self.weights {
            Weights::Uniform(weight) => std::slice::from_ref(weight),
            Weights::PerPair(_, distinct) => distinct,
        }
    }

    /// The index among [`Terms::pairs`] of continuous joint `joint` of the graph, when it is
    /// scored.
    pub fn joint_term(&self, joint: usize) -> Option<usize> {
        match &self.joints {
            Joints::Leading(count) => (joint < *count).then_some(joint),
            Joints::Map(map) => map[joint],
        }
    }

    /// Per candidate tile its partners in the scored pairs, with what each chosen partner
    /// adds.
    pub fn partners(&self, tiles: usize) -> Vec<Vec<(usize, f64)>> {
        let mut partners = vec![Vec::new(); tiles];
        for (_, [a, b], weight) in self.iter() {
            partners[a].push((b, weight));
            partners[b].push((a, weight));
        }
        partners
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{PolyMesh, Topology};

    fn grid(n: usize) -> PolyMesh {
        crate::mesh::generate::grid(n, n)
    }

    #[test]
    fn one_zone_gives_the_terms_of_its_bond() {
        let mesh = grid(6);
        let topology = Topology::new(&mesh).unwrap();
        let graph = DualGraph::new(&mesh, &topology, &[]);
        for bond in [
            Bond::Stack,
            Bond::Staggered { weight: 0.5 },
            Bond::RunningBond { weight: 0.3 },
            Bond::Herringbone { weight: 0.5 },
            Bond::BasketWeave { weight: 0.5 },
        ] {
            let uniform = Terms::uniform(&graph, bond);
            let zoned = Terms::zoned(&graph, &vec![bond; mesh.face_count()]);
            let scored = |t: &Terms<'_>| {
                let mut pairs: Vec<([usize; 2], f64)> = t
                    .iter()
                    .filter(|(_, _, w)| *w != 0.0)
                    .map(|(_, p, w)| (p, w))
                    .collect();
                pairs.sort_by_key(|p| p.0);
                pairs
            };
            assert_eq!(scored(&uniform), scored(&zoned), "{bond:?}");
            assert_eq!(uniform.is_empty(), zoned.is_empty(), "{bond:?}");
            if !zoned.is_empty() {
                assert_eq!(uniform.common_weight(), zoned.common_weight(), "{bond:?}");
            }
            for j in 0..graph.continuous_joints().len() {
                assert_eq!(
                    uniform.joint_term(j).map(|i| uniform.pairs()[i]),
                    zoned.joint_term(j).map(|i| zoned.pairs()[i]),
                    "{bond:?}"
                );
            }
        }
    }

    #[test]
    fn pairs_across_a_zone_border_score_by_their_faces_in_each_zone() {
        let mesh = grid(6);
        let topology = Topology::new(&mesh).unwrap();
        let graph = DualGraph::new(&mesh, &topology, &[]);
        // Columns 0-2 staggered, 3-5 running bond.
        let zones: Vec<Bond> = (0..mesh.face_count())
            .map(|f| {
                if f % 6 < 3 {
                    Bond::Staggered { weight: 0.5 }
                } else {
                    Bond::RunningBond { weight: 0.5 }
                }
            })
            .collect();
        let terms = Terms::zoned(&graph, &zones);
        assert!(!terms.is_empty());
        assert_eq!(terms.common_weight(), None);
        assert_eq!(terms.largest_reward(), 0.5);
        let mut across = 0;
        for (_, [a, b], weight) in terms.iter() {
            let faces: Vec<usize> = [a, b]
                .iter()
                .flat_map(|&t| graph.tiles()[t].faces)
                .collect();
            let left = faces.iter().filter(|&f| f % 6 < 3).count() as f64;
            let joint = graph.continuous_joints().contains(&[a, b]);
            let shifted = graph.shifted_pairs().contains(&[a, b]);
            // A quarter per face: -w for a joint on the staggered side, +w for a shifted
            // pair on the running-bond side.
            let want = if joint { -0.5 * left / 4.0 } else { 0.0 }
                + if shifted {
                    0.5 * (4.0 - left) / 4.0
                } else {
                    0.0
                };
            assert_eq!(weight, want, "{a} {b}");
            if left > 0.0 && left < 4.0 {
                across += 1;
            }
        }
        assert!(across > 0);
        // Quarters of 0.5: every objective a multiple of 1/8.
        assert_eq!(terms.quantum(1.0), Some(0.125));
        assert_eq!(terms.quantum(0.5), Some(0.125));
        // Both zones have pairs.
        assert!(terms.iter().any(|(_, _, w)| w < 0.0));
        assert!(terms.iter().any(|(_, _, w)| w > 0.0));
    }
}
