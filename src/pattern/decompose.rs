//! Decomposition bound: the faces are split into patches of a few hundred faces and the
//! relaxed program of every patch ([`Patch`]) is solved exactly. Every pattern of the
//! whole mesh, cut along the patch borders, is a solution of each patch's relaxation of
//! the same value share, so the patch optima add up to an upper bound on the whole
//! optimum. Unlike the maximum matching, the bound sees the half tiles and continuous
//! joints that singularities and ragged boundaries force within a patch, which is where
//! the optimum of such meshes falls short of the matching (issue: certified matching).
//!
//! Such a defect is only proven when it lies deep inside its patch: near a free border the
//! relaxation can move it out. So each round's larger patches are centred on the defects
//! the last round's relaxations could not avoid, and built as unions of the last round's
//! patches, which lets them start from its bounds.

use std::collections::VecDeque;
use std::time::Instant;

use super::bound;
use super::mip;
use super::program::{Patch, Restriction};
use super::{DualGraph, Formulation, PatternError, Terms, linear};
use crate::control::Control;

/// A patch may take this many times its even share of the time left.
const PATCH_SHARE: f64 = 3.0;

/// A partition of the faces into patches of about equal size.
pub(super) struct Partition {
    /// Patch of every face; faces in no candidate tile belong to no patch (`usize::MAX`).
    pub patch_of: Vec<usize>,
    /// Number of patches.
    pub count: usize,
    /// Patches `0..centred` are centred on the sources given to [`partition`].
    pub centred: usize,
    /// For a partition made by [`coarsen`], what was proven on the finer one.
    carried: Option<Carried>,
}

/// Bounds proven on a finer partition, carried over to the coarser one that [`coarsen`]
/// made of its patches.
struct Carried {
    /// Sum of the bounds of each patch's parts.
    patch_bounds: Vec<f64>,
    /// The patch owning each pair of the bond's relation: the one holding its finer owner.
    owner: Vec<usize>,
}

/// Splits the faces into patches of about `size` faces. Seeds first go to `sources`
/// (faces where earlier relaxations found forced defects, strongest first; one closer to an
/// earlier seed than a patch's radius is dropped), so that each such defect lies in the
/// middle of its patch, far from the free border that would let the relaxation escape it.
/// The rest are placed one by one at the face farthest (in steps between adjacent faces)
/// from those placed so far (the first one at the first usable face, or for `variant > 0`
/// at another face, so that partitions of the same size differ); faces go to their nearest
/// seed (ties to the earlier seed); then [`LLOYD_ROUNDS`] times every seed but the sources
/// moves to its patch's deepest face and the faces are assigned again, which evens out the
/// patches. Deterministic.
fn partition(graph: &DualGraph, size: usize, variant: usize, sources: &[usize]) -> Partition {
    let faces = graph.face_count();
    let usable: Vec<usize> = (0..faces)
        .filter(|&f| !graph.face_tiles(f).is_empty())
        .collect();
    let wanted = usable.len().div_ceil(size.max(1)).max(1);
    let mut patch_of = vec![usize::MAX; faces];
    let mut distance = vec![usize::MAX; faces];
    let mut seeds = Vec::new();
    // A patch of a quad mesh within r steps of its seed has about 2 r^2 faces.
    let radius = ((size as f64 / 2.0).sqrt() as usize).max(1);
    for &source in sources
        .iter()
        .filter(|&&f| f < faces && !graph.face_tiles(f).is_empty())
    {
        if distance[source] >= radius {
            grow(graph, source, seeds.len(), &mut distance, &mut patch_of);
            seeds.push(source);
        }
    }
    let pinned = seeds.len();
    if variant > 0 && !usable.is_empty() {
        let first = usable[variant.wrapping_mul(7919) % usable.len()];
        if distance[first] > 0 {
            grow(graph, first, seeds.len(), &mut distance, &mut patch_of);
            seeds.push(first);
        }
    }
    while seeds.len() < wanted || usable.iter().any(|&f| patch_of[f] == usize::MAX) {
        // The farthest face; unreached faces (another connected piece) first.
        let Some(seed) = usable
            .iter()
            .copied()
            .max_by_key(|&f| (distance[f], std::cmp::Reverse(f)))
        else {
            break;
        };
        if distance[seed] == 0 {
            break;
        }
        grow(graph, seed, seeds.len(), &mut distance, &mut patch_of);
        seeds.push(seed);
    }
    for _ in 0..LLOYD_ROUNDS {
        let mut moved = deepest_faces(graph, &patch_of, seeds.len());
        moved[..pinned].copy_from_slice(&seeds[..pinned]);
        if moved == seeds {
            break;
        }
        seeds = moved;
        distance.iter_mut().for_each(|d| *d = usize::MAX);
        patch_of.iter_mut().for_each(|p| *p = usize::MAX);
        for (p, &seed) in seeds.iter().enumerate() {
            grow(graph, seed, p, &mut distance, &mut patch_of);
        }
    }
    Partition {
        patch_of,
        count: seeds.len(),
        centred: pinned,
        carried: None,
    }
}

/// A round's partition: [`partition`] of `size`, made of the patches of the last round's
/// (`finer`, with what it proved) when there is one, so that its bounds carry over.
pub(super) fn next_partition(
    graph: &DualGraph,
    size: usize,
    variant: usize,
    sources: &[usize],
    finer: Option<(Partition, Proven)>,
) -> Partition {
    let fresh = partition(graph, size, variant, sources);
    match finer {
        Some((last, proven)) => coarsen(&fresh, &last, &proven),
        None => fresh,
    }
}

/// `coarse` rounded to unions of the patches of `finer`, carrying over what was `proven` on
/// `finer` (see [`bound()`]): every patch of `finer` goes whole to the patch of `coarse` that
/// holds most of its faces (the lowest index among equals); patches left empty are dropped,
/// the others keep their order, so the centred ones stay first.
fn coarsen(coarse: &Partition, finer: &Partition, proven: &Proven) -> Partition {
    let mut overlaps: Vec<(usize, usize)> = finer
        .patch_of
        .iter()
        .zip(&coarse.patch_of)
        .filter(|(q, p)| **q != usize::MAX && **p != usize::MAX)
        .map(|(&q, &p)| (q, p))
        .collect();
    overlaps.sort_unstable();
    // The coarse patch with most faces of each finer patch.
    let mut chosen: Vec<(usize, usize)> = vec![(0, usize::MAX); finer.count];
    for run in overlaps.chunk_by(|a, b| a == b) {
        let (q, p) = run[0];
        if run.len() > chosen[q].0 || (run.len() == chosen[q].0 && p < chosen[q].1) {
            chosen[q] = (run.len(), p);
        }
    }
    let mut used = vec![false; coarse.count];
    chosen
        .iter()
        .filter(|(_, p)| *p != usize::MAX)
        .for_each(|&(_, p)| used[p] = true);
    let mut renumbered = vec![usize::MAX; coarse.count];
    let mut count = 0;
    for p in (0..coarse.count).filter(|&p| used[p]) {
        renumbered[p] = count;
        count += 1;
    }
    let parent: Vec<usize> = chosen
        .iter()
        .map(|&(_, p)| {
            if p == usize::MAX {
                usize::MAX
            } else {
                renumbered[p]
            }
        })
        .collect();
    let patch_of = finer
        .patch_of
        .iter()
        .map(|&q| {
            if q == usize::MAX {
                usize::MAX
            } else {
                parent[q]
            }
        })
        .collect();
    let centred = (0..coarse.centred).filter(|&p| used[p]).count();
    let mut patch_bounds = vec![0.0; count];
    proven
        .patch_bounds
        .iter()
        .enumerate()
        .for_each(|(q, b)| patch_bounds[parent[q]] += b);
    let owner = proven.owner.iter().map(|&q| parent[q]).collect();
    Partition {
        patch_of,
        count,
        centred,
        carried: Some(Carried {
            patch_bounds,
            owner,
        }),
    }
}

/// Times seeds are moved to the middle of their patches.
const LLOYD_ROUNDS: usize = 3;

/// Breadth-first from `seed`, claiming for `patch` every face closer to it than to the seed
/// that claimed it before.
fn grow(
    graph: &DualGraph,
    seed: usize,
    patch: usize,
    distance: &mut [usize],
    patch_of: &mut [usize],
) {
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
    let edge = |f: usize| {
        graph.face_tiles(f).len() < 4 || graph.neighbours(f).any(|g| patch_of[g] != patch_of[f])
    };
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

/// Upper bound on the objective of `bond` from the patches of `partition` (`None` when the
/// deadline passes before it holds), and where the relaxations found forced defects. Forced
/// pairs only restrict the whole program, so the relaxations are solved over all candidate
/// tiles and the bound holds for them too.
///
/// On a partition made by [`coarsen`], every patch starts from the sum of its parts' bounds
/// proven on the finer partition and the pairs keep their owners, so the result is never
/// weaker than the finer partition's and a patch the deadline leaves unsolved loses nothing.
/// On a fresh partition a stack or staggered patch starts from half a tile per face; a
/// running-bond patch has no such simple bound, and the deadline then gives `None`.
///
/// A patch where the `incumbent` already scores its starting bound would return exactly
/// that: such patches are not solved. The others are solved those centred on sources first,
/// then by how far the incumbent falls short of their starting bound, the largest first,
/// each if its linear program is expected to finish within its share of the time left. A
/// patch cut short by the deadline contributes its solver bound.
///
/// With `linear`, each patch's linear relaxation is solved instead, by Clp's barrier (see
/// `linear`): a weaker bound, found far sooner, so that patches can be larger (and no
/// sources are reported).
#[expect(
    clippy::too_many_arguments,
    reason = "the stage's inputs, its limits and its control"
)]
pub(super) fn bound(
    graph: &DualGraph,
    terms: &Terms<'_>,
    linear: bool,
    partition: &Partition,
    incumbent: &[bool],
    deadline: Instant,
    control: &mut Control<'_>,
    progress: &impl Fn() -> f64,
) -> Result<Proven, PatternError> {
    let tiles = graph.tiles();
    // Only a reward lifts a patch above half a tile per face.
    let running = terms.largest_reward() > 0.0;
    let mut members = vec![Vec::new(); partition.count];
    for (f, &p) in partition
        .patch_of
        .iter()
        .enumerate()
        .filter(|(_, p)| **p != usize::MAX)
    {
        members[p].push(f);
    }
    let (owner, mut patch_bound) = match &partition.carried {
        Some(carried) => (carried.owner.clone(), carried.patch_bounds.clone()),
        None => {
            // Each pair belongs to the first patch both its tiles reach, else to the patch of
            // its first tile's first face (a reward pair must be counted somewhere).
            let reaches =
                |t: usize, p: usize| tiles[t].faces.iter().any(|&f| partition.patch_of[f] == p);
            let owner: Vec<usize> = terms
                .pairs()
                .iter()
                .map(|&[a, b]| {
                    tiles[a]
                        .faces
                        .iter()
                        .map(|&f| partition.patch_of[f])
                        .filter(|&p| reaches(b, p))
                        .min()
                        .unwrap_or(partition.patch_of[tiles[a].faces[0]])
                })
                .collect();
            // Half a tile per face, the trivial bound of a stack or staggered patch.
            let start = members
                .iter()
                .map(|m| {
                    if running {
                        f64::INFINITY
                    } else {
                        0.5 * m.len() as f64
                    }
                })
                .collect();
            (owner, start)
        }
    };

    let mut order: Vec<usize> = (0..partition.count).collect();
    let mut shortfall = vec![f64::INFINITY; partition.count];
    if patch_bound.iter().all(|b| b.is_finite()) {
        // How far the incumbent's share in each patch (half per covered face, plus its owned
        // pairs' terms) falls short of the patch's bound.
        let mut covered = vec![false; graph.face_count()];
        for (t, _) in incumbent.iter().enumerate().filter(|(_, on)| **on) {
            tiles[t].faces.iter().for_each(|&f| covered[f] = true);
        }
        for (p, m) in members.iter().enumerate() {
            shortfall[p] = patch_bound[p] - 0.5 * m.iter().filter(|&&f| covered[f]).count() as f64;
        }
        for (i, [a, b], per_pair) in terms.iter() {
            if incumbent[a] && incumbent[b] && owner[i] != usize::MAX {
                shortfall[owner[i]] -= per_pair;
            }
        }
        order.retain(|&p| shortfall[p] > 1e-9);
    }
    // Patches around known forced defects first, as they hold most of what can be proven.
    order.sort_by(|&p, &q| {
        (q < partition.centred)
            .cmp(&(p < partition.centred))
            .then(shortfall[q].total_cmp(&shortfall[p]))
            .then(p.cmp(&q))
    });

    let free = vec![true; tiles.len()];
    let fixed = vec![false; tiles.len()];
    let mut faces = vec![false; graph.face_count()];
    let mut sources = Vec::new();
    for (k, &p) in order.iter().enumerate() {
        let now = Instant::now();
        if now >= deadline {
            break;
        }
        // A fair share of the time left, so one hard patch cannot starve the others; a patch
        // cut short still gives its solver's bound.
        let share = (deadline - now)
            .mul_f64(PATCH_SHARE / (order.len() - k) as f64)
            .min(deadline - now);
        let expected = if linear {
            linear::expected_seconds(members[p].len())
        } else {
            mip::expected_linear_seconds(members[p].len())
        };
        if expected > share.as_secs_f64() {
            continue;
        }
        members[p].iter().for_each(|&f| faces[f] = true);
        let owned: Vec<bool> = owner.iter().map(|&o| o == p).collect();
        let patch = Patch {
            faces: &faces,
            owned: &owned,
        };
        // The solver's bound, and for an integer program the relaxed pattern it found.
        let (solver_bound, chosen) = if linear {
            let found = linear::bound(graph, terms, Some(patch), share, control, progress)?;
            (found.map_or(f64::INFINITY, |found| found.value), None)
        } else {
            let restriction = Restriction {
                free: &free,
                fixed: &fixed,
                patch: Some(patch),
            };
            let outcome = mip::solve(
                graph,
                terms,
                Formulation::Strengthened,
                &restriction,
                share,
                0.0,
                control,
                progress,
            )?;
            (outcome.bound, outcome.chosen)
        };
        let solved = bound::round_down(solver_bound, terms, 0.5, 0.5 * members[p].len() as f64);
        patch_bound[p] = patch_bound[p].min(solved);
        if let (Some(chosen), false) = (&chosen, running) {
            let shortfall = 0.5 * members[p].len() as f64 - patch_bound[p];
            if shortfall > 1e-9 {
                let defects = defect_faces(graph, terms, &owned, &faces, chosen);
                let face = middle(graph, &defects).unwrap_or(members[p][0]);
                sources.push(Source { face, shortfall });
            }
        }
        members[p].iter().for_each(|&f| faces[f] = false);
    }
    sources.sort_by(|a, b| {
        b.shortfall
            .total_cmp(&a.shortfall)
            .then(a.face.cmp(&b.face))
    });
    let total: f64 = patch_bound.iter().sum();
    Ok(Proven {
        value: total.is_finite().then_some(total),
        sources,
        patch_bounds: patch_bound,
        owner,
    })
}

/// What [`bound()`] proved.
pub(super) struct Proven {
    /// The upper bound; `None` for a running bond whose patches were not all solved.
    pub value: Option<f64>,
    /// Where the solved relaxations had to leave defects, the largest shortfall first: the
    /// seeds of the next, larger patches.
    pub sources: Vec<Source>,
    /// Bound of every patch (infinite for a running-bond patch not solved).
    patch_bounds: Vec<f64>,
    /// The patch owning each pair of the bond's relation.
    owner: Vec<usize>,
}

/// The middle of the defects a patch relaxation could not avoid.
pub(super) struct Source {
    /// A face among the defects, the one closest to the others.
    pub face: usize,
    /// Objective the patch's relaxation falls short of half a tile per face.
    pub shortfall: f64,
}

/// Faces of `patch` that the relaxed pattern `chosen` leaves uncovered or gives a penalty
/// pair (of the `owned` pairs of `terms`).
fn defect_faces(
    graph: &DualGraph,
    terms: &Terms<'_>,
    owned: &[bool],
    patch: &[bool],
    chosen: &[bool],
) -> Vec<usize> {
    let tiles = graph.tiles();
    let mut covered = vec![false; graph.face_count()];
    for (t, _) in chosen.iter().enumerate().filter(|(_, on)| **on) {
        tiles[t].faces.iter().for_each(|&f| covered[f] = true);
    }
    let mut defects: Vec<usize> = (0..graph.face_count())
        .filter(|&f| patch[f] && !covered[f])
        .collect();
    for (_, [a, b], _) in terms
        .iter()
        .filter(|&(i, [a, b], weight)| weight < 0.0 && owned[i] && chosen[a] && chosen[b])
    {
        defects.extend(
            tiles[a]
                .faces
                .iter()
                .chain(&tiles[b].faces)
                .filter(|&&f| patch[f]),
        );
    }
    defects.sort_unstable();
    defects.dedup();
    defects
}

/// The face of `faces` with the least sum of steps to the others (the lowest index among
/// equals), or `None` for no faces.
fn middle(graph: &DualGraph, faces: &[usize]) -> Option<usize> {
    let mut distance = vec![usize::MAX; graph.face_count()];
    let mut claimed = vec![0; graph.face_count()];
    let mut best: Option<(usize, usize)> = None;
    for &from in faces {
        distance.iter_mut().for_each(|d| *d = usize::MAX);
        grow(graph, from, 0, &mut distance, &mut claimed);
        let total: usize = faces
            .iter()
            .map(|&f| distance[f].min(graph.face_count()))
            .sum();
        if best.is_none_or(|(_, b)| total < b) {
            best = Some((from, total));
        }
    }
    best.map(|(f, _)| f)
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::mesh::{PolyMesh, Topology, generate};
    use crate::pattern::{Bond, Method, PatternOptions, SolveStatus, solve};

    /// A grid with every third boundary face (by a fixed hash) removed.
    pub(in crate::pattern) fn ragged(n: usize) -> PolyMesh {
        let grid = generate::grid(n, n);
        let edge = |f: usize| f % n == 0 || f % n == n - 1 || f / n == 0 || f / n == n - 1;
        let faces = (0..grid.face_count())
            .filter(|&f| !(edge(f) && f.wrapping_mul(2654435761) % 3 == 0))
            .map(|f| grid.faces()[f].clone());
        PolyMesh::new(grid.positions().to_vec(), faces.collect()).unwrap()
    }

    #[test]
    fn patch_bounds_are_never_below_the_proven_optimum() {
        for mesh in [ragged(7), ragged(8), generate::grid(6, 7)] {
            let topology = Topology::new(&mesh).unwrap();
            let graph = DualGraph::new(&mesh, &topology, &[]);
            let faces = mesh.face_count();
            // Zones: bands of staggered, herringbone and running bond.
            let bands: Vec<Bond> = (0..faces)
                .map(|f| {
                    [
                        Bond::Staggered { weight: 0.5 },
                        Bond::Herringbone { weight: 0.5 },
                        Bond::RunningBond { weight: 0.5 },
                    ][f * 3 / faces]
                })
                .collect();
            for (bond, zones) in [
                (Bond::Stack, None),
                (Bond::Staggered { weight: 0.5 }, None),
                (Bond::Staggered { weight: 2.0 }, None),
                (Bond::RunningBond { weight: 0.5 }, None),
                (Bond::Herringbone { weight: 0.5 }, None),
                (Bond::BasketWeave { weight: 0.5 }, None),
                (Bond::Stack, Some(bands)),
            ] {
                let terms = match &zones {
                    Some(zones) => Terms::zoned(&graph, zones),
                    None => Terms::uniform(&graph, bond),
                };
                let bond = if zones.is_some() {
                    Bond::RunningBond { weight: 0.5 }
                } else {
                    bond
                };
                let options = PatternOptions {
                    bond,
                    zones,
                    method: Method::Mip,
                    time_limit: std::time::Duration::from_secs(20),
                    ..PatternOptions::default()
                };
                let optimum = solve(&mesh, &options).unwrap();
                assert_eq!(optimum.status, SolveStatus::Optimal);
                // No incumbent: every patch is solved.
                let nothing = vec![false; graph.tiles().len()];
                for (size, linear) in [6, 12, 25]
                    .into_iter()
                    .flat_map(|size| [(size, false), (size, true)])
                {
                    let partition = partition(&graph, size, 0, &[]);
                    assert!(partition.count > 1);
                    let deadline = Instant::now() + std::time::Duration::from_secs(20);
                    let bound = super::bound(
                        &graph,
                        &terms,
                        linear,
                        &partition,
                        &nothing,
                        deadline,
                        &mut Control::none(),
                        &|| 0.0,
                    )
                    .unwrap()
                    .value
                    .unwrap();
                    let what = if linear {
                        "linear relaxations"
                    } else {
                        "patches"
                    };
                    assert!(
                        bound >= optimum.objective - 1e-6,
                        "{bond:?}, {what} of {size}: bound {bound} < optimum {}",
                        optimum.objective
                    );
                    assert!(
                        bound <= 0.5 * mesh.face_count() as f64 + 1e-6
                            || matches!(bond, Bond::RunningBond { .. })
                    );
                }
                // Coarser patches built from finer ones, centred on the finer round's sources:
                // never weaker than the finer bound, never below the optimum.
                let finer_partition = partition(&graph, 6, 0, &[]);
                let deadline = Instant::now() + std::time::Duration::from_secs(20);
                let finer = super::bound(
                    &graph,
                    &terms,
                    false,
                    &finer_partition,
                    &nothing,
                    deadline,
                    &mut Control::none(),
                    &|| 0.0,
                )
                .unwrap();
                let sources: Vec<usize> = finer.sources.iter().map(|s| s.face).collect();
                let coarse = coarsen(
                    &partition(&graph, 20, 0, &sources),
                    &finer_partition,
                    &finer,
                );
                assert!(coarse.count < finer_partition.count);
                let refined = super::bound(
                    &graph,
                    &terms,
                    false,
                    &coarse,
                    &nothing,
                    deadline,
                    &mut Control::none(),
                    &|| 0.0,
                )
                .unwrap();
                let (finer, refined) = (finer.value.unwrap(), refined.value.unwrap());
                assert!(
                    refined <= finer + 1e-9,
                    "{bond:?}: coarser bound {refined} above the finer {finer}"
                );
                assert!(
                    refined >= optimum.objective - 1e-6,
                    "{bond:?}: coarser bound {refined} < optimum {}",
                    optimum.objective
                );
            }
        }
    }

    #[test]
    fn partitions_cover_every_usable_face_with_patches_of_about_the_size_asked() {
        let mesh = generate::grid(30, 20);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let partition = partition(&graph, 100, 0, &[]);
        assert_eq!(partition.count, 6);
        assert!(partition.patch_of.iter().all(|&p| p < partition.count));
        let mut sizes = vec![0; partition.count];
        partition.patch_of.iter().for_each(|&p| sizes[p] += 1);
        assert!(sizes.iter().all(|&s| (40..=200).contains(&s)), "{sizes:?}");

        // Sources seed the first patches (one too close to another is dropped) and keep their
        // place; a coarsening is a union of whole patches.
        let sources = [0, 1, 310];
        let centred = super::partition(&graph, 100, 0, &sources);
        assert_eq!(centred.centred, 2);
        assert_eq!((centred.patch_of[0], centred.patch_of[310]), (0, 1));
        let nothing = Proven {
            value: Some(0.0),
            sources: Vec::new(),
            patch_bounds: vec![0.0; centred.count],
            owner: Vec::new(),
        };
        let coarse = coarsen(&super::partition(&graph, 200, 0, &[]), &centred, &nothing);
        assert!(coarse.count < centred.count);
        let mut parent = vec![usize::MAX; centred.count];
        for f in 0..mesh.face_count() {
            let q = centred.patch_of[f];
            assert!(
                parent[q] == usize::MAX || parent[q] == coarse.patch_of[f],
                "patch {q} split"
            );
            parent[q] = coarse.patch_of[f];
        }
    }
}
