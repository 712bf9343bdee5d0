//! Large-neighbourhood search: re-solve small windows of the pattern exactly with CBC while
//! the rest stays fixed, centred on the pattern's defects (half tiles, continuous joints,
//! tiles without shifted neighbours). Small windows keep every CBC call short, so the time
//! limit is checked often.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::mip;
use super::program::Restriction;
use super::score::evaluate;
use super::{DualGraph, Formulation, PatternError, Terms};
use crate::control::Control;

/// Faces per window in the first sweep; doubled after a sweep without improvement.
const FIRST_WINDOW: usize = 48;
/// Largest window tried.
const LAST_WINDOW: usize = 384;
/// Longest single window solve.
const WINDOW_TIME: Duration = Duration::from_secs(2);

/// Improves `chosen` (which includes the `fixed` tiles) in place until a sweep with the
/// largest window finds nothing better or `deadline` passes.
pub(super) fn improve(
    graph: &DualGraph,
    terms: &Terms<'_>,
    fixed: &[bool],
    chosen: &mut [bool],
    deadline: Instant,
    control: &mut Control<'_>,
    progress: &impl Fn() -> f64,
) -> Result<(), PatternError> {
    let mut size = FIRST_WINDOW;
    let mut current = evaluate(graph, chosen, terms).objective;
    while size <= LAST_WINDOW {
        let mut improved = false;
        let mut covered = vec![false; graph.face_count()];
        for seed in defects(graph, terms, chosen) {
            if covered[seed] {
                continue;
            }
            let now = Instant::now();
            if now >= deadline {
                return Ok(());
            }
            if !control.keep_going(progress()) {
                return Err(PatternError::Cancelled);
            }
            let window = ball(graph, seed, size);
            window.iter().for_each(|&f| covered[f] = true);
            let mut inside = vec![false; graph.face_count()];
            window.iter().for_each(|&f| inside[f] = true);
            let free: Vec<bool> = graph
                .tiles()
                .iter()
                .enumerate()
                .map(|(t, tile)| !fixed[t] && tile.faces.iter().all(|&f| inside[f]))
                .collect();
            let held: Vec<bool> = chosen.iter().zip(&free).map(|(&on, &f)| on && !f).collect();
            let restriction = Restriction {
                free: &free,
                fixed: &held,
                patch: None,
            };
            let limit = (deadline - now).min(WINDOW_TIME);
            let outcome = mip::solve(
                graph,
                terms,
                Formulation::Strengthened,
                &restriction,
                limit,
                0.0,
                control,
                progress,
            )?;
            let Some(window_choice) = outcome.chosen else {
                continue;
            };
            let candidate: Vec<bool> = held
                .iter()
                .zip(&window_choice)
                .zip(&free)
                .map(|((&h, &w), &f)| h || (w && f))
                .collect();
            let value = evaluate(graph, &candidate, terms).objective;
            if value > current + 1e-9 && is_matching(graph, &candidate) {
                chosen.copy_from_slice(&candidate);
                current = value;
                improved = true;
            }
        }
        if !improved {
            size *= 2;
        }
    }
    Ok(())
}

/// Faces where the pattern may be improved, in index order.
fn defects(graph: &DualGraph, terms: &Terms<'_>, chosen: &[bool]) -> Vec<usize> {
    let mut flagged = vec![false; graph.face_count()];
    let mut covered = vec![false; graph.face_count()];
    for (t, _) in chosen.iter().enumerate().filter(|(_, on)| **on) {
        graph.tiles()[t]
            .faces
            .iter()
            .for_each(|&f| covered[f] = true);
    }
    for f in 0..graph.face_count() {
        flagged[f] = !covered[f] && !graph.face_tiles(f).is_empty();
    }
    let mut flag_tile = |t: usize| {
        graph.tiles()[t]
            .faces
            .iter()
            .for_each(|&f| flagged[f] = true)
    };
    // A penalised pair: both its tiles. A reward: tiles with fewer than two rewarded
    // partners (a running bond's inner tiles have two).
    let mut rewarded = vec![0usize; chosen.len()];
    let mut rewards = false;
    for (_, [a, b], weight) in terms.iter() {
        if weight < 0.0 && chosen[a] && chosen[b] {
            flag_tile(a);
            flag_tile(b);
        } else if weight > 0.0 {
            rewards = true;
            if chosen[a] && chosen[b] {
                rewarded[a] += 1;
                rewarded[b] += 1;
            }
        }
    }
    if rewards {
        // In zones, only the tiles that could have a rewarded partner.
        let partners = (terms.common_weight().is_none()).then(|| terms.partners(chosen.len()));
        let rewardable = |t: usize| {
            partners
                .as_ref()
                .is_none_or(|p| p[t].iter().any(|&(_, w)| w > 0.0))
        };
        for t in (0..chosen.len()).filter(|&t| chosen[t] && rewarded[t] < 2) {
            if rewardable(t) {
                flag_tile(t);
            }
        }
    }
    (0..graph.face_count()).filter(|&f| flagged[f]).collect()
}

/// Up to `size` faces closest to `seed` (breadth-first over candidate tiles, index order).
fn ball(graph: &DualGraph, seed: usize, size: usize) -> Vec<usize> {
    let mut seen = vec![false; graph.face_count()];
    let mut order = Vec::with_capacity(size);
    let mut queue = VecDeque::from([seed]);
    seen[seed] = true;
    while let Some(f) = queue.pop_front() {
        order.push(f);
        if order.len() == size {
            break;
        }
        for g in graph.neighbours(f) {
            if !std::mem::replace(&mut seen[g], true) {
                queue.push_back(g);
            }
        }
    }
    order
}

/// True when no face is in two chosen tiles.
pub(super) fn is_matching(graph: &DualGraph, chosen: &[bool]) -> bool {
    let mut used = vec![false; graph.face_count()];
    graph
        .tiles()
        .iter()
        .zip(chosen)
        .filter(|(_, c)| **c)
        .all(|(tile, _)| {
            tile.faces
                .iter()
                .all(|&f| !std::mem::replace(&mut used[f], true))
        })
}
