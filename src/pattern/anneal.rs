//! Simulated annealing over matchings: a fast local search that moves the pattern's defects
//! (half tiles and continuous joints) around until they cancel or settle where they cost
//! least. Every move changes one or two tiles, so its effect on the objective is counted
//! from the tiles' bond partners in constant time; millions of moves take well under a
//! second. Used before the exact window search, which then only has to polish.
//!
//! Moves, at a random face `f`:
//! * `f` is a half tile and so is its neighbour `g`: lay the tile `(f, g)`;
//! * `f` is a half tile and its neighbour `g` lies in the tile `(g, h)`: shift that tile
//!   onto `(f, g)`, which moves the half tile from `f` to `h`;
//! * `f` lies in a tile: take the tile up (two half tiles);
//!
//! and at a random regular vertex:
//! * the four faces around a regular vertex hold two parallel tiles: turn them by 90 degrees.
//!
//! Deterministic: a fixed-seed generator, no threads.

use std::time::Instant;

use super::score::evaluate;
use super::{DualGraph, Terms};

/// Most moves per face at each temperature.
const MOVES_PER_FACE: usize = 400;
/// Temperature steps, geometric from the first temperature down to [`LAST_TEMPERATURE`]
/// (in objective units: a tile is 1, a joint `w`).
const STEPS: usize = 12;
pub(super) const LAST_TEMPERATURE: f64 = 0.03;
/// First temperature of a run from a constructive start.
pub(super) const FIRST_TEMPERATURE: f64 = 0.3;
/// Moves this machine-independent budget assumes per second, so that a run planned for a
/// time limit almost always ends before it and stays deterministic: about three quarters
/// of the 18 million a second measured here (2 cores, 2026; 1400-2600 faces). A slower
/// machine stops its runs at the deadline instead, with the best pattern seen.
const NOMINAL_MOVES_PER_SECOND: f64 = 14e6;

/// A schedule: how hot to start, how many moves, which random sequence.
pub(super) struct Schedule {
    /// First temperature.
    pub temperature: f64,
    /// Moves per temperature step in all.
    pub moves_per_step: usize,
    /// Seed of the move generator.
    pub seed: u64,
}

impl Schedule {
    /// Up to [`MOVES_PER_FACE`] moves per face and step, fewer when that would not fit in
    /// `budget` at [`NOMINAL_MOVES_PER_SECOND`]: depends only on the mesh size and the budget.
    pub(super) fn for_budget(
        faces: usize,
        budget: std::time::Duration,
        temperature: f64,
        seed: u64,
    ) -> Self {
        let affordable = (budget.as_secs_f64() * NOMINAL_MOVES_PER_SECOND / STEPS as f64) as usize;
        Self {
            temperature,
            moves_per_step: (MOVES_PER_FACE * faces).min(affordable).max(faces),
            seed,
        }
    }
}

/// A small, fast, deterministic generator (xorshift64*).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (((self.next() >> 11) as u128 * n as u128) >> 53) as usize
    }

    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The pattern as annealing changes it.
struct State<'a> {
    graph: &'a DualGraph,
    /// Per tile: its partners in the scored pairs, with what each adds when both are
    /// chosen (`-w` for a penalty, `+w` for a reward).
    partners: Vec<Vec<(usize, f64)>>,
    chosen: Vec<bool>,
    /// The chosen tile on each face.
    tile_on: Vec<Option<usize>>,
    /// Tiles that may not change (forced ones).
    locked: Vec<bool>,
    value: f64,
    /// Faces in no chosen tile (that could be in one), in any order, and where each sits
    /// in that list (`usize::MAX`: not a half tile), so a half tile is drawn in O(1).
    half_tiles: Vec<usize>,
    half_tile_slot: Vec<usize>,
}

impl State<'_> {
    /// What tile `t` adds to the objective, chosen or not: its own 1 and its bond pairs
    /// with the chosen tiles.
    fn share(&self, t: usize) -> f64 {
        1.0 + self.partners[t]
            .iter()
            .filter(|&&(u, _)| self.chosen[u])
            .map(|&(_, w)| w)
            .sum::<f64>()
    }

    fn set(&mut self, t: usize, on: bool) {
        self.chosen[t] = on;
        for f in self.graph.tiles()[t].faces {
            self.tile_on[f] = on.then_some(t);
            if on {
                let slot = std::mem::replace(&mut self.half_tile_slot[f], usize::MAX);
                self.half_tiles.swap_remove(slot);
                if let Some(&moved) = self.half_tiles.get(slot) {
                    self.half_tile_slot[moved] = slot;
                }
            } else {
                self.half_tile_slot[f] = self.half_tiles.len();
                self.half_tiles.push(f);
            }
        }
    }
}

/// Moves between two looks at the clock and the caller (a few milliseconds).
const MOVES_BETWEEN_CHECKS: usize = 1 << 16;

/// Anneals `chosen` (a matching that includes the `locked` tiles) in place under `terms` and
/// leaves there the best pattern seen. Stops early at `deadline` or when `keep_going` (asked
/// every few milliseconds) says so; returns `false` in the second case.
pub(super) fn anneal(
    graph: &DualGraph,
    terms: &Terms<'_>,
    locked: &[bool],
    chosen: &mut [bool],
    schedule: &Schedule,
    deadline: Instant,
    keep_going: &mut dyn FnMut() -> bool,
) -> bool {
    let faces: Vec<usize> = (0..graph.face_count())
        .filter(|&f| !graph.face_tiles(f).is_empty())
        .collect();
    if faces.is_empty() {
        return true;
    }
    let partners = terms.partners(graph.tiles().len());
    let mut tile_on = vec![None; graph.face_count()];
    for (t, _) in chosen.iter().enumerate().filter(|(_, on)| **on) {
        graph.tiles()[t]
            .faces
            .iter()
            .for_each(|&f| tile_on[f] = Some(t));
    }
    let value = evaluate(graph, chosen, terms).objective;
    let mut half_tile_slot = vec![usize::MAX; graph.face_count()];
    let half_tiles: Vec<usize> = faces
        .iter()
        .copied()
        .filter(|&f| tile_on[f].is_none())
        .collect();
    for (slot, &f) in half_tiles.iter().enumerate() {
        half_tile_slot[f] = slot;
    }
    let mut state = State {
        graph,
        partners,
        chosen: chosen.to_vec(),
        tile_on,
        locked: locked.to_vec(),
        value,
        half_tiles,
        half_tile_slot,
    };
    let mut best = state.value;
    let stars = graph.regular_vertex_stars();
    // xorshift needs a non-zero state.
    let mut rng = Rng(schedule.seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let first = schedule.temperature.max(LAST_TEMPERATURE);
    for step in 0..STEPS {
        let temperature = first * (LAST_TEMPERATURE / first).powf(step as f64 / (STEPS - 1) as f64);
        for k in 0..schedule.moves_per_step {
            if k % MOVES_BETWEEN_CHECKS == 0 {
                if !keep_going() {
                    return false;
                }
                if Instant::now() >= deadline {
                    return true;
                }
            }
            // Three moves in eight start at a half tile, where most of the change happens;
            // one in eight turns two tiles.
            let delta = match rng.below(8) {
                0 if !stars.is_empty() => try_turn(
                    &mut state,
                    stars[rng.below(stars.len())],
                    temperature,
                    &mut rng,
                ),
                1..4 if !state.half_tiles.is_empty() => {
                    let f = state.half_tiles[rng.below(state.half_tiles.len())];
                    try_face_move(&mut state, f, temperature, &mut rng)
                }
                _ => try_face_move(
                    &mut state,
                    faces[rng.below(faces.len())],
                    temperature,
                    &mut rng,
                ),
            };
            state.value += delta;
            if state.value > best + 1e-9 {
                best = state.value;
                chosen.copy_from_slice(&state.chosen);
            }
        }
    }
    true
}

/// Metropolis rule: improvements always, a loss `-delta` with probability `e^(delta / T)`.
fn accept(delta: f64, temperature: f64, rng: &mut Rng) -> bool {
    delta >= -1e-12 || rng.unit() < (delta / temperature).exp()
}

/// One of the face moves at `f`; returns the objective change made (0 if rejected).
fn try_face_move(state: &mut State<'_>, f: usize, temperature: f64, rng: &mut Rng) -> f64 {
    let graph = state.graph;
    match state.tile_on[f] {
        Some(t) => {
            if state.locked[t] {
                return 0.0;
            }
            let delta = -state.share(t);
            if accept(delta, temperature, rng) {
                state.set(t, false);
                return delta;
            }
            0.0
        }
        None => {
            let around = graph.face_tiles(f);
            let t = around[rng.below(around.len())];
            let [a, b] = graph.tiles()[t].faces;
            let g = if a == f { b } else { a };
            match state.tile_on[g] {
                None => {
                    let delta = state.share(t);
                    if accept(delta, temperature, rng) {
                        state.set(t, true);
                        return delta;
                    }
                    0.0
                }
                Some(s) => {
                    if state.locked[s] {
                        return 0.0;
                    }
                    // s and t share g, so neither is a bond partner of the other.
                    let delta = state.share(t) - state.share(s);
                    if accept(delta, temperature, rng) {
                        state.set(s, false);
                        state.set(t, true);
                        return delta;
                    }
                    0.0
                }
            }
        }
    }
}

/// Turns two parallel tiles around a regular vertex (`[a, b, c, d]` in cyclic order, `a`
/// with `c` or `b` with `d` chosen) by 90 degrees; returns the objective change made.
fn try_turn(
    state: &mut State<'_>,
    [a, b, c, d]: [usize; 4],
    temperature: f64,
    rng: &mut Rng,
) -> f64 {
    let (from, to) = if state.chosen[a] && state.chosen[c] {
        ([a, c], [b, d])
    } else if state.chosen[b] && state.chosen[d] {
        ([b, d], [a, c])
    } else {
        return 0.0;
    };
    if from.iter().any(|&t| state.locked[t]) {
        return 0.0;
    }
    let before = state.value_around(&from);
    state.set(from[0], false);
    state.set(from[1], false);
    state.set(to[0], true);
    state.set(to[1], true);
    let delta = state.value_around(&to) - before;
    if accept(delta, temperature, rng) {
        return delta;
    }
    state.set(to[0], false);
    state.set(to[1], false);
    state.set(from[0], true);
    state.set(from[1], true);
    0.0
}

impl State<'_> {
    /// The objective share of the chosen tiles `pair` (both chosen, disjoint): their own
    /// tiles and every bond pair they are in, the pair between them counted once.
    fn value_around(&self, pair: &[usize; 2]) -> f64 {
        let [p, q] = *pair;
        let inner = self.partners[p]
            .iter()
            .find(|&&(u, _)| u == q)
            .map_or(0.0, |&(_, w)| w);
        self.share(p) + self.share(q) - inner
    }
}
