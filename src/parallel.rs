//! Deterministic data parallelism for the loops that dominate large meshes: the remesher's
//! conjugate gradients (their operators and vector updates).
//!
//! Work over `n` items is cut into parts by `n` alone ([`parts`]), never by the machine, and
//! what the parts give is combined in part order; the threads only decide which part runs
//! where. So a result is the same bit for bit on one core or many (the guide's
//! determinism), and below [`MIN_PART`] items there is one part: the plain sequential loop,
//! with no thread started.
//!
//! Threads are scoped ([`std::thread::scope`]) and started per call: a few tens of
//! microseconds against milliseconds of work per call at the sizes that are split. Callers'
//! callbacks ([`crate::control::Control`]) never run on them. `TILEPATTERN_THREADS` caps the
//! threads (1: no thread is started at all).

use std::cell::RefCell;
use std::ops::Range;
use std::sync::OnceLock;

/// Fewest items a part gets: smaller loops run as one part.
pub(crate) const MIN_PART: usize = 16_384;

/// Most parts a loop is cut into (and so most threads used).
pub(crate) const MAX_PARTS: usize = 2;

/// Number of parts `items` are cut into: as many as give each [`MIN_PART`] items, at least
/// 1 and at most [`MAX_PARTS`]. Depends on `items` only.
pub(crate) fn parts(items: usize) -> usize {
    (items / MIN_PART).clamp(1, MAX_PARTS)
}

/// Length of every part but the last when `items` are cut into [`parts`]`(items)`.
fn part_len(items: usize) -> usize {
    items.div_ceil(parts(items)).max(1)
}

/// The ranges of the parts of `0..items`, in order.
fn ranges(items: usize) -> impl Iterator<Item = Range<usize>> {
    let len = part_len(items);
    (0..parts(items)).map(move |k| (k * len).min(items)..((k + 1) * len).min(items))
}

/// Threads a split loop may use: the machine's parallelism, or `TILEPATTERN_THREADS`.
fn threads() -> usize {
    static THREADS: OnceLock<usize> = OnceLock::new();
    *THREADS.get_or_init(|| {
        std::env::var("TILEPATTERN_THREADS")
            .ok()
            .and_then(|v| v.trim().parse::<usize>().ok())
            .filter(|&t| t > 0)
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
    })
}

/// Runs every task and returns what each gave, in task order: on the calling thread alone
/// when there is one task or one thread, otherwise on up to [`threads`] scoped threads, task
/// `k` on thread `k mod threads`.
pub(crate) fn run<T: Send, F: FnOnce() -> T + Send>(tasks: Vec<F>) -> Vec<T> {
    let threads = threads().min(tasks.len());
    if threads <= 1 {
        return tasks.into_iter().map(|task| task()).collect();
    }
    let count = tasks.len();
    let mut groups: Vec<Vec<(usize, F)>> = (0..threads).map(|_| Vec::new()).collect();
    for (k, task) in tasks.into_iter().enumerate() {
        groups[k % threads].push((k, task));
    }
    let mut done: Vec<Option<T>> = (0..count).map(|_| None).collect();
    std::thread::scope(|scope| {
        let mut groups = groups.into_iter();
        let own = groups.next().unwrap_or_default();
        let handles: Vec<_> = groups
            .map(|group| {
                scope.spawn(move || {
                    group
                        .into_iter()
                        .map(|(k, task)| (k, task()))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        for (k, value) in own.into_iter().map(|(k, task)| (k, task())) {
            done[k] = Some(value);
        }
        for handle in handles {
            match handle.join() {
                Ok(values) => {
                    for (k, value) in values {
                        done[k] = Some(value);
                    }
                }
                Err(panic) => std::panic::resume_unwind(panic),
            }
        }
    });
    done.into_iter().flatten().collect()
}

/// Sum over the parts of `0..items` of `part(range)`, added in part order.
pub(crate) fn sum(items: usize, part: impl Fn(Range<usize>) -> f64 + Sync) -> f64 {
    let part = &part;
    run(ranges(items).map(|r| move || part(r)).collect())
        .into_iter()
        .sum()
}

/// `a . b`, summed part by part (in order within a part, then over the parts in order).
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    sum(a.len(), |r| {
        a[r.clone()].iter().zip(&b[r]).map(|(x, y)| x * y).sum()
    })
}

/// Calls `each(range, chunk)` on the parts of `data`, each with its own chunk, and returns
/// the sum of what they give, in part order.
pub(crate) fn chunks_mut(
    data: &mut [f64],
    each: impl Fn(Range<usize>, &mut [f64]) -> f64 + Sync,
) -> f64 {
    let items = data.len();
    let each = &each;
    let tasks: Vec<_> = data
        .chunks_mut(part_len(items))
        .zip(ranges(items))
        .map(|(chunk, r)| move || each(r, chunk))
        .collect();
    run(tasks).into_iter().sum()
}

/// [`chunks_mut`] over two vectors of one length, cut alike.
pub(crate) fn chunks_mut2(
    a: &mut [f64],
    b: &mut [f64],
    each: impl Fn(Range<usize>, &mut [f64], &mut [f64]) -> f64 + Sync,
) -> f64 {
    assert_eq!(a.len(), b.len(), "vectors of one length");
    let items = a.len();
    let len = part_len(items);
    let each = &each;
    let tasks: Vec<_> = a
        .chunks_mut(len)
        .zip(b.chunks_mut(len))
        .zip(ranges(items))
        .map(|((a, b), r)| move || each(r, a, b))
        .collect();
    run(tasks).into_iter().sum()
}

/// Calls `each(i, &mut a[i], &mut b[i])` for every `i`, on up to [`MAX_PARTS`] of the
/// [`threads`] once there are [`MIN_COSTLY`] items or more. For work where each item stands alone (nothing is
/// summed across items), so that the result is the same however the items are split; meant
/// for costly items such as closest-point queries, which pay for threads at far fewer items
/// than the loops [`parts`] splits.
pub(crate) fn each_mut2<A: Send, B: Send>(
    a: &mut [A],
    b: &mut [B],
    each: impl Fn(usize, &mut A, &mut B) + Sync,
) {
    assert_eq!(a.len(), b.len(), "vectors of one length");
    let len = costly_part_len(a.len());
    let each = &each;
    let tasks: Vec<_> = a
        .chunks_mut(len)
        .zip(b.chunks_mut(len))
        .enumerate()
        .map(|(k, (a, b))| {
            move || {
                for (i, (a, b)) in a.iter_mut().zip(b).enumerate() {
                    each(k * len + i, a, b);
                }
            }
        })
        .collect();
    run(tasks);
}

/// `each(i)` for every `i` in `0..items`, in order, computed on up to [`MAX_PARTS`] of the
/// [`threads`] once there are [`MIN_COSTLY`] items or more: for independent costly items
/// (closest-point queries, the samples of a face), so the result is the same however they
/// are split. Whatever the caller then sums over the results it sums in item order, as the
/// plain loop did.
pub(crate) fn map<T: Send>(items: usize, each: impl Fn(usize) -> T + Sync) -> Vec<T> {
    map_with(items, || (), |(), i| each(i))
}

/// [`map`] for items that need scratch space: each part makes its own with `scratch()` and
/// lends it to `each(scratch, i)` for its items in turn. What an item gives must not depend
/// on what earlier items left in the scratch.
pub(crate) fn map_with<S, T: Send>(
    items: usize,
    scratch: impl Fn() -> S + Sync,
    each: impl Fn(&mut S, usize) -> T + Sync,
) -> Vec<T> {
    let len = costly_part_len(items);
    let (each, scratch) = (&each, &scratch);
    let tasks: Vec<_> = (0..items.div_ceil(len))
        .map(|k| {
            move || {
                let mut own = scratch();
                ((k * len).min(items)..((k + 1) * len).min(items))
                    .map(|i| each(&mut own, i))
                    .collect()
            }
        })
        .collect();
    run::<Vec<T>, _>(tasks).into_iter().flatten().collect()
}

/// Fewest costly items [`each_mut2`] and [`map`] split.
pub(crate) const MIN_COSTLY: usize = 1024;

/// Length of the parts costly, independent items are handed out in ([`each_mut2`],
/// [`map_with`]): all in one part below [`MIN_COSTLY`], otherwise one part per thread, at
/// most [`MAX_PARTS`]. The split decides only which thread computes an item, never what it
/// gives.
fn costly_part_len(items: usize) -> usize {
    let count = if items < MIN_COSTLY {
        1
    } else {
        threads().min(MAX_PARTS)
    };
    items.div_ceil(count).max(1)
}

/// Sums of per-item terms scattered into a vector (an operator applied edge by edge, each
/// edge adding to its two ends), split by items: the first part adds into the output itself,
/// every other into a spare vector of its own, and the spares are then added to the output
/// in part order. The spares are kept between calls.
#[derive(Default)]
pub(crate) struct Scatter {
    spare: RefCell<Vec<Vec<f64>>>,
}

impl Scatter {
    /// Adds `add(range, out)` over the parts of `0..items` into `out` (which holds what the
    /// caller put there before). `add` must only add into `out`, for the items of `range`.
    pub(crate) fn add(
        &self,
        items: usize,
        out: &mut [f64],
        add: impl Fn(Range<usize>, &mut [f64]) + Sync,
    ) {
        let count = parts(items);
        if count == 1 {
            add(0..items, out);
            return;
        }
        let mut spare = self.spare.borrow_mut();
        spare.resize_with(count - 1, Vec::new);
        for s in spare.iter_mut() {
            s.resize(out.len(), 0.0);
        }
        let add = &add;
        let mut ranges = ranges(items);
        let first = ranges.next().unwrap_or(0..0);
        {
            let own: &mut [f64] = &mut *out;
            let mut tasks: Vec<Box<dyn FnOnce() + Send + '_>> = Vec::with_capacity(count);
            tasks.push(Box::new(move || add(first, own)));
            for (s, r) in spare.iter_mut().zip(ranges) {
                let s: &mut [f64] = s;
                // Zeroed by the part's own thread, beside the first part's work.
                tasks.push(Box::new(move || {
                    s.fill(0.0);
                    add(r, s);
                }));
            }
            run(tasks);
        }
        let spare = &*spare;
        chunks_mut(out, |r, chunk| {
            for s in spare {
                for (o, x) in chunk.iter_mut().zip(&s[r.clone()]) {
                    *o += x;
                }
            }
            0.0
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_gives_every_item_once_in_order() {
        for items in [0, 1, MIN_COSTLY - 1, MIN_COSTLY, 3 * MIN_COSTLY + 7] {
            let got = map(items, |i| i * i);
            assert_eq!(got, (0..items).map(|i| i * i).collect::<Vec<_>>());
        }
    }

    #[test]
    fn parts_depend_on_the_size_only_and_cover_it_in_order() {
        assert_eq!(parts(10), 1);
        assert_eq!(parts(MIN_PART * 2), 2);
        assert_eq!(parts(MIN_PART * 100), MAX_PARTS);
        for items in [0, 1, 5, MIN_PART * 3 + 7, MIN_PART * 100 + 3] {
            let all: Vec<usize> = ranges(items).flatten().collect();
            assert_eq!(all, (0..items).collect::<Vec<_>>());
        }
    }

    #[test]
    fn a_scatter_adds_each_part_in_turn_to_what_the_output_held() {
        // Items i add i-dependent terms to two outputs, as an edge adds to its two ends.
        let items = MIN_PART * 3 + 5;
        let n = 1000;
        let ends = |i: usize| [(i * 7) % n, (i * 13 + 1) % n];
        let term = |i: usize| 1.0 / (1.0 + i as f64);
        let add = |range: Range<usize>, out: &mut [f64]| {
            for i in range {
                let [a, b] = ends(i);
                out[a] += term(i);
                out[b] -= 0.5 * term(i);
            }
        };
        let start: Vec<f64> = (0..n).map(|k| k as f64 * 1e-3).collect();
        // What the split must give: the first part into the output, every other part into
        // zeros, then those added in order.
        let mut expected = start.clone();
        let mut ranges = ranges(items);
        add(ranges.next().unwrap(), &mut expected);
        let others: Vec<Vec<f64>> = ranges
            .map(|r| {
                let mut own = vec![0.0; n];
                add(r, &mut own);
                own
            })
            .collect();
        for (k, e) in expected.iter_mut().enumerate() {
            for own in &others {
                *e += own[k];
            }
        }
        let scatter = Scatter::default();
        for _ in 0..2 {
            // Twice: the spare vectors kept from the first call start from zero again.
            let mut out = start.clone();
            scatter.add(items, &mut out, add);
            assert!(out == expected);
        }
        // And the sum is the plain loop's up to rounding.
        let mut plain = start.clone();
        add(0..items, &mut plain);
        for (x, y) in plain.iter().zip(&expected) {
            assert!((x - y).abs() < 1e-9, "{x} {y}");
        }
    }

    #[test]
    fn each_item_is_visited_once_with_its_own_index() {
        for items in [3, MIN_COSTLY, MIN_COSTLY * 5 + 3] {
            let mut a: Vec<usize> = vec![0; items];
            let mut b: Vec<f64> = (0..items).map(|i| i as f64).collect();
            each_mut2(&mut a, &mut b, |i, a, b| {
                *a += i + 1;
                *b *= 2.0;
            });
            assert!(a.iter().enumerate().all(|(i, &a)| a == i + 1));
            assert!(b.iter().enumerate().all(|(i, &b)| b == 2.0 * i as f64));
        }
    }

    #[test]
    fn tasks_come_back_in_order() {
        let tasks: Vec<_> = (0..9).map(|k| move || k * k).collect();
        assert_eq!(run(tasks), (0..9).map(|k| k * k).collect::<Vec<_>>());
    }
}
