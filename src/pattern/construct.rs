//! Constructive starts: a running bond laid along the quad strips of the mesh, and courses
//! laid along rings parallel to the boundary.
//!
//! In a regular region a running bond is the checkerboard colouring of the faces plus a
//! consistent "forward" direction: every face of colour 0 pairs with its forward neighbour.
//! It has no continuous joint at all, so it is also an optimal stagger away from boundaries
//! and singularities (the "lay the bond along quad strips"). Both are propagated
//! breadth-first over the dual graph; where a singularity makes the transport inconsistent,
//! the first visit wins and the window search repairs the seam.

use std::collections::VecDeque;

use crate::mesh::Topology;

use super::score::evaluate;
use super::{DualGraph, Terms};

/// The better of the two running bonds (rows along either edge family of the seed face),
/// completed greedily, never touching faces of `fixed` tiles.
pub(super) fn running_bond(
    graph: &DualGraph,
    topology: &Topology,
    terms: &Terms<'_>,
    fixed: &[bool],
) -> Vec<bool> {
    (0..2)
        .map(|seed_slot| {
            let mut chosen = strip_pairs(graph, topology, fixed, seed_slot);
            complete_greedily(graph, terms, fixed, &mut chosen);
            chosen
        })
        .max_by(|a, b| {
            evaluate(graph, a, terms)
                .objective
                .total_cmp(&evaluate(graph, b, terms).objective)
                .then(std::cmp::Ordering::Greater)
        })
        .expect("two candidates")
}

/// Pairs each colour-0 face with its forward neighbour, after propagating colour and
/// forward edge slot from the lowest-index face of each connected part.
fn strip_pairs(
    graph: &DualGraph,
    topology: &Topology,
    fixed: &[bool],
    seed_slot: usize,
) -> Vec<bool> {
    let faces = graph.face_count();
    let mut used = faces_of(graph, fixed);
    let mut state: Vec<Option<(u8, usize)>> = vec![None; faces];
    let mut queue = VecDeque::new();
    for seed in 0..faces {
        if state[seed].is_some() || graph.face_tiles(seed).is_empty() {
            continue;
        }
        state[seed] = Some((0, seed_slot));
        queue.push_back(seed);
        while let Some(f) = queue.pop_front() {
            let (colour, forward) = state[f].expect("queued faces have a state");
            for (k, &e) in topology.face_edges(f).iter().enumerate() {
                let Some(g) = topology.edges()[e].other_face(f) else {
                    continue;
                };
                if state[g].is_some() || graph.tile_between(f, g).is_none() {
                    continue;
                }
                let k_in_g = topology
                    .face_edges(g)
                    .iter()
                    .position(|&x| x == e)
                    .expect("shared edge");
                // Forward slot transported across the shared edge; see the module notes.
                let turn = (k + 4 - forward) % 4;
                state[g] = Some((1 - colour, (k_in_g + 6 - turn) % 4));
                queue.push_back(g);
            }
        }
    }
    let mut chosen = vec![false; graph.tiles().len()];
    for f in 0..faces {
        let Some((0, forward)) = state[f] else {
            continue;
        };
        let e = topology.face_edges(f)[forward];
        let Some(g) = topology.edges()[e].other_face(f) else {
            continue;
        };
        let (Some(t), Some((1, _))) = (graph.tile_between(f, g), state[g]) else {
            continue;
        };
        if !used[f] && !used[g] {
            used[f] = true;
            used[g] = true;
            chosen[t] = true;
        }
    }
    chosen
}

/// Courses parallel to the boundary, as masons lay a vault from its supports and as the
/// paper's optimal staggered grids look (Fig. 5): faces are grouped in rings by their
/// distance to the boundary, each ring is walked face to face and paired along the walk, and
/// of the two phases of each walk the one scoring better against the rings already laid is
/// kept, which staggers neighbouring courses. Closed meshes start from their first face.
pub(super) fn boundary_courses(
    graph: &DualGraph,
    topology: &Topology,
    terms: &Terms<'_>,
    fixed: &[bool],
) -> Vec<bool> {
    let faces = graph.face_count();
    let mut ring = vec![usize::MAX; faces];
    let mut queue = VecDeque::new();
    for (f, ring_of_f) in ring.iter_mut().enumerate() {
        let on_boundary = topology
            .face_edges(f)
            .iter()
            .any(|&e| topology.edges()[e].is_boundary());
        if on_boundary && !graph.face_tiles(f).is_empty() {
            *ring_of_f = 0;
            queue.push_back(f);
        }
    }
    if queue.is_empty() {
        if let Some(seed) = (0..faces).find(|&f| !graph.face_tiles(f).is_empty()) {
            ring[seed] = 0;
            queue.push_back(seed);
        }
    }
    while let Some(f) = queue.pop_front() {
        for g in graph.neighbours(f) {
            if ring[g] == usize::MAX {
                ring[g] = ring[f] + 1;
                queue.push_back(g);
            }
        }
    }

    let partners = terms.partners(graph.tiles().len());
    let mut chosen = fixed.to_vec();
    let mut used = faces_of(graph, fixed);
    let mut walked = vec![false; faces];
    let mut order: Vec<usize> = (0..faces).filter(|&f| ring[f] != usize::MAX).collect();
    order.sort_by_key(|&f| (ring[f], f));
    for start in order {
        if walked[start] || used[start] {
            continue;
        }
        let mut walk = vec![start];
        walked[start] = true;
        while let Some(next) = graph
            .neighbours(*walk.last().expect("non-empty"))
            .filter(|&g| ring[g] == ring[start] && !walked[g] && !used[g])
            .min()
        {
            walked[next] = true;
            walk.push(next);
        }
        let phase = |offset: usize| -> Vec<usize> {
            walk.windows(2)
                .skip(offset)
                .step_by(2)
                .filter_map(|w| graph.tile_between(w[0], w[1]))
                .collect()
        };
        let (even, odd) = (phase(0), phase(1));
        // What laying `tiles` adds: one per tile and the bond term of every pair they make
        // with laid tiles or among themselves (counted once).
        let gain = |tiles: &[usize]| {
            let mut value = tiles.len() as f64;
            for (k, &t) in tiles.iter().enumerate() {
                value += partners[t]
                    .iter()
                    .filter(|&&(u, _)| chosen[u] || tiles[..k].contains(&u))
                    .map(|&(_, w)| w)
                    .sum::<f64>();
            }
            value
        };
        let best = if gain(&odd) > gain(&even) { odd } else { even };
        for t in best {
            chosen[t] = true;
            graph.tiles()[t].faces.iter().for_each(|&f| used[f] = true);
        }
    }
    complete_greedily(graph, terms, fixed, &mut chosen);
    chosen
}

/// Adds free tiles, in index order, whenever they raise the objective.
pub(super) fn complete_greedily(
    graph: &DualGraph,
    terms: &Terms<'_>,
    fixed: &[bool],
    chosen: &mut [bool],
) {
    let mut used = faces_of(graph, fixed);
    for (t, _) in chosen.iter().enumerate().filter(|(_, on)| **on) {
        graph.tiles()[t].faces.iter().for_each(|&f| used[f] = true);
    }
    let partners = terms.partners(graph.tiles().len());
    for t in 0..graph.tiles().len() {
        let [a, b] = graph.tiles()[t].faces;
        if used[a] || used[b] {
            continue;
        }
        let on: f64 = partners[t]
            .iter()
            .filter(|&&(u, _)| chosen[u] || fixed[u])
            .map(|&(_, w)| w)
            .sum();
        if 1.0 + on > 0.0 {
            used[a] = true;
            used[b] = true;
            chosen[t] = true;
        }
    }
}

/// Faces covered by the tiles marked in `tiles`.
fn faces_of(graph: &DualGraph, tiles: &[bool]) -> Vec<bool> {
    let mut used = vec![false; graph.face_count()];
    for (t, _) in tiles.iter().enumerate().filter(|(_, on)| **on) {
        graph.tiles()[t].faces.iter().for_each(|&f| used[f] = true);
    }
    used
}
