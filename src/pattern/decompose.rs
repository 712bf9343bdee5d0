//! Decomposition bound: the faces are split into patches of a few hundred faces and the
//! relaxed program of every patch ([`mip::Patch`]) is solved exactly. Every pattern of the
//! whole mesh, cut along the patch borders, is a solution of each patch's relaxation of
//! the same value share, so the patch optima add up to an upper bound on the whole
//! optimum. Unlike the maximum matching, the bound sees the half tiles and continuous
//! joints that singularities and ragged boundaries force within a patch, which is where
//! the optimum of such meshes falls short of the matching (issue: certified matching).

use std::collections::VecDeque;
use std::time::Instant;

use super::mip::{self, Patch, Restriction};
use super::{Bond, DualGraph, Formulation, PatternError};
use crate::control::Control;

/// A patch may take this many times its even share of the time left.
const PATCH_SHARE: f64 = 3.0;

/// A partition of the faces into patches of about equal size.
pub(super) struct Partition {
    /// Patch of every face; faces in no candidate tile belong to no patch (`usize::MAX`).
    pub patch_of: Vec<usize>,
    /// Number of patches.
    pub count: usize,
}

/// Splits the faces into patches of about `size` faces: seeds placed one by one at the face
/// farthest (in steps between adjacent faces) from those placed so far (the first one at
/// the first usable face, or for `variant > 0` at another face, so that partitions of the
/// same size differ), faces assigned to their nearest seed (ties to the earlier seed), then
/// [`LLOYD_ROUNDS`] times every seed moved to its patch's deepest face and the faces
/// assigned again, which evens out the patches. Deterministic.
pub(super) fn partition(graph: &DualGraph, size: usize, variant: usize) -> Partition {
    let faces = graph.face_count();
    let usable: Vec<usize> = (0..faces).filter(|&f| !graph.face_tiles(f).is_empty()).collect();
    let wanted = usable.len().div_ceil(size.max(1)).max(1);
    let mut patch_of = vec![usize::MAX; faces];
    let mut distance = vec![usize::MAX; faces];
    let mut seeds = Vec::new();
    if variant > 0 && !usable.is_empty() {
        let first = usable[variant.wrapping_mul(7919) % usable.len()];
        grow(graph, first, 0, &mut distance, &mut patch_of);
        seeds.push(first);
    }
    while seeds.len() < wanted || usable.iter().any(|&f| patch_of[f] == usize::MAX) {
        // The farthest face; unreached faces (another connected piece) first.
        let Some(seed) = usable.iter().copied().max_by_key(|&f| (distance[f], std::cmp::Reverse(f))) else { break };
        if distance[seed] == 0 {
            break;
        }
        grow(graph, seed, seeds.len(), &mut distance, &mut patch_of);
        seeds.push(seed);
    }
    for _ in 0..LLOYD_ROUNDS {
        let deepest = deepest_faces(graph, &patch_of, seeds.len());
        if deepest == seeds {
            break;
        }
        seeds = deepest;
        distance.iter_mut().for_each(|d| *d = usize::MAX);
        patch_of.iter_mut().for_each(|p| *p = usize::MAX);
        for (p, &seed) in seeds.iter().enumerate() {
            grow(graph, seed, p, &mut distance, &mut patch_of);
        }
    }
    Partition { patch_of, count: seeds.len() }
}

/// Times seeds are moved to the middle of their patches.
const LLOYD_ROUNDS: usize = 3;

/// Breadth-first from `seed`, claiming for `patch` every face closer to it than to the seed
/// that claimed it before.
fn grow(graph: &DualGraph, seed: usize, patch: usize, distance: &mut [usize], patch_of: &mut [usize]) {
    let mut queue = VecDeque::from([seed]);
    distance[seed] = 0;
    patch_of[seed] = patch;
    while let Some(f) = queue.pop_front() {
        for g in graph.neighbours(f) {
            if distance[f] + 1 < distance[g] {
                distance[g] = distance[f] + 1;
                patch_of[g] = patch;
                queue.push_back(g);
            }
        }
    }
}

/// For every patch, its face farthest from the patch's edge (faces next to another patch or
/// to the mesh boundary), the lowest index among equals.
fn deepest_faces(graph: &DualGraph, patch_of: &[usize], count: usize) -> Vec<usize> {
    let faces = graph.face_count();
    let edge = |f: usize| graph.face_tiles(f).len() < 4 || graph.neighbours(f).any(|g| patch_of[g] != patch_of[f]);
    let mut depth = vec![usize::MAX; faces];
    let mut queue = VecDeque::new();
    for f in (0..faces).filter(|&f| patch_of[f] != usize::MAX && edge(f)) {
        depth[f] = 0;
        queue.push_back(f);
    }
    while let Some(f) = queue.pop_front() {
        for g in graph.neighbours(f) {
            if patch_of[g] == patch_of[f] && depth[g] == usize::MAX {
                depth[g] = depth[f] + 1;
                queue.push_back(g);
            }
        }
    }
    let mut deepest = vec![usize::MAX; count];
    for f in (0..faces).filter(|&f| patch_of[f] != usize::MAX) {
        let p = patch_of[f];
        if deepest[p] == usize::MAX || depth[f] > depth[deepest[p]] {
            deepest[p] = f;
        }
    }
    deepest
}

/// Upper bound on the objective of `bond` from the patches of `partition`, or `None` when
/// the deadline passes before it holds. Forced pairs only restrict the whole program, so
/// the relaxations are solved over all candidate tiles and the bound holds for them too.
///
/// For stack and staggered bonds no patch can score more than half a tile per face, and a
/// patch where the `incumbent` already scores that much would return exactly that: such
/// patches are not solved, and the others are solved in order of the incumbent's shortfall
/// in them, the largest first. A patch cut short by the deadline contributes its solver
/// bound; patches not reached contribute half a tile per face. A running bond has no
/// per-patch bound this simple, so every patch is solved and the deadline gives `None`.
pub(super) fn bound(
    graph: &DualGraph,
    bond: Bond,
    partition: &Partition,
    incumbent: &[bool],
    deadline: Instant,
    control: &mut Control<'_>,
    progress: &impl Fn() -> f64,
) -> Result<Option<f64>, PatternError> {
    let tiles = graph.tiles();
    let (relation, per_pair) = graph.bond_pairs(bond);
    // Each pair belongs to the first patch both its tiles reach, else to the patch of its
    // first tile's first face (a reward pair must be counted somewhere).
    let reaches = |t: usize, p: usize| tiles[t].faces.iter().any(|&f| partition.patch_of[f] == p);
    let owner: Vec<usize> = relation
        .iter()
        .map(|&[a, b]| tiles[a].faces.iter().map(|&f| partition.patch_of[f]).filter(|&p| reaches(b, p)).min().unwrap_or(partition.patch_of[tiles[a].faces[0]]))
        .collect();

    let mut members = vec![Vec::new(); partition.count];
    for (f, &p) in partition.patch_of.iter().enumerate().filter(|(_, p)| **p != usize::MAX) {
        members[p].push(f);
    }
    // Half a tile per face: each patch's trivial bound.
    let trivial: Vec<f64> = members.iter().map(|m| 0.5 * m.len() as f64).collect();
    let mut order: Vec<usize> = (0..partition.count).collect();
    let running = matches!(bond, Bond::RunningBond { .. });
    let mut shortfall = vec![0.0; partition.count];
    if !running {
        // The incumbent's share in each patch: half per covered face, minus owned joints.
        let mut covered = vec![false; graph.face_count()];
        for (t, _) in incumbent.iter().enumerate().filter(|(_, on)| **on) {
            tiles[t].faces.iter().for_each(|&f| covered[f] = true);
        }
        for (p, m) in members.iter().enumerate() {
            shortfall[p] = 0.5 * m.iter().filter(|&&f| !covered[f]).count() as f64;
        }
        for (i, &[a, b]) in relation.iter().enumerate() {
            if incumbent[a] && incumbent[b] && owner[i] != usize::MAX {
                shortfall[owner[i]] -= per_pair;
            }
        }
        order.retain(|&p| shortfall[p] > 1e-9);
        order.sort_by(|&p, &q| shortfall[q].total_cmp(&shortfall[p]).then(p.cmp(&q)));
    }

    let free = vec![true; tiles.len()];
    let fixed = vec![false; tiles.len()];
    let mut faces = vec![false; graph.face_count()];
    let mut patch_bound = trivial;
    for (k, &p) in order.iter().enumerate() {
        let now = Instant::now();
        if now >= deadline {
            return Ok((!running).then(|| patch_bound.iter().sum()));
        }
        // A fair share of the time left, so one hard patch cannot starve the others; a patch
        // cut short still gives its solver's bound.
        let share = (deadline - now).mul_f64(PATCH_SHARE / (order.len() - k) as f64).min(deadline - now);
        members[p].iter().for_each(|&f| faces[f] = true);
        let owned: Vec<bool> = owner.iter().map(|&o| o == p).collect();
        let restriction = Restriction { free: &free, fixed: &fixed, patch: Some(Patch { faces: &faces, owned: &owned }) };
        let outcome = mip::solve(graph, bond, Formulation::Strengthened, &restriction, share, control, progress)?;
        members[p].iter().for_each(|&f| faces[f] = false);
        if outcome.bound.is_finite() {
            patch_bound[p] = if running { outcome.bound } else { outcome.bound.min(patch_bound[p]) };
        } else if running {
            return Ok(None);
        }
    }
    Ok(Some(patch_bound.iter().sum()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{PolyMesh, Topology, generate};
    use crate::pattern::{Method, PatternOptions, SolveStatus, solve};

    /// A grid with every third boundary face (by a fixed hash) removed.
    fn ragged(n: usize) -> PolyMesh {
        let grid = generate::grid(n, n);
        let edge = |f: usize| f % n == 0 || f % n == n - 1 || f / n == 0 || f / n == n - 1;
        let faces = (0..grid.face_count()).filter(|&f| !(edge(f) && f.wrapping_mul(2654435761) % 3 == 0)).map(|f| grid.faces()[f].clone());
        PolyMesh::new(grid.positions().to_vec(), faces.collect()).unwrap()
    }

    #[test]
    fn patch_bounds_are_never_below_the_proven_optimum() {
        for mesh in [ragged(7), ragged(8), generate::grid(6, 7)] {
            let topology = Topology::new(&mesh).unwrap();
            let graph = DualGraph::new(&mesh, &topology, &[]);
            for bond in [Bond::Stack, Bond::Staggered { weight: 0.5 }, Bond::Staggered { weight: 2.0 }, Bond::RunningBond { weight: 0.5 }] {
                let options = PatternOptions { bond, method: Method::Mip, time_limit: std::time::Duration::from_secs(20), ..PatternOptions::default() };
                let optimum = solve(&mesh, &options).unwrap();
                assert_eq!(optimum.status, SolveStatus::Optimal);
                // No incumbent: every patch is solved.
                let nothing = vec![false; graph.tiles().len()];
                for size in [6, 12, 25] {
                    let partition = partition(&graph, size, 0);
                    assert!(partition.count > 1);
                    let deadline = Instant::now() + std::time::Duration::from_secs(20);
                    let bound = super::bound(&graph, bond, &partition, &nothing, deadline, &mut Control::none(), &|| 0.0).unwrap().unwrap();
                    assert!(bound >= optimum.objective - 1e-6, "{bond:?}, patches of {size}: bound {bound} < optimum {}", optimum.objective);
                    assert!(bound <= 0.5 * mesh.face_count() as f64 + 1e-6 || matches!(bond, Bond::RunningBond { .. }));
                }
            }
        }
    }

    #[test]
    fn partitions_cover_every_usable_face_with_patches_of_about_the_size_asked() {
        let mesh = generate::grid(30, 20);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let partition = partition(&graph, 100, 0);
        assert_eq!(partition.count, 6);
        assert!(partition.patch_of.iter().all(|&p| p < partition.count));
        let mut sizes = vec![0; partition.count];
        partition.patch_of.iter().for_each(|&p| sizes[p] += 1);
        assert!(sizes.iter().all(|&s| (40..=200).contains(&s)), "{sizes:?}");
    }
}
