//! Bound from the linear relaxation of the whole program (eqs. 1-3, with the star rows for
//! eq. 2), or of one patch's relaxed program (see `decompose`), solved by Clp's
//! interior-point method.
//!
//! For the relaxation `max c.x` subject to `A x <= b` and `0 <= x <= 1`, any prices `p >= 0`
//! on the rows bound the optimum, and so the integer optimum (weak duality):
//! `L(p) = b.p + sum_j max(0, c_j - A_j.p)` ([`Model::dual_bound`](crate::solver::Model::dual_bound)).
//! The bound is computed here from the prices the
//! barrier leaves, whether it converged or the time limit stopped it, so it holds whatever
//! the solver's tolerances and status; at convergence it is the relaxation's optimum.
//!
//! With the star rows this optimum is within a few tiles of the integer optimum on meshes
//! whose singularities and ragged boundaries force defects (the QuadriFlow hypar: 691.51
//! against 688.5 found), where a patch decomposition has to cut across the seams that join
//! them; and the barrier reaches it in a fraction of the simplex method's time (0.12 s
//! against 2.4 s there), on a program written with one joint column per regular vertex.

use std::time::Duration;

use super::program::{Patch, Program, Restriction};
use super::{DualGraph, Formulation, PatternError, Terms, worker};
use crate::control::Control;
use crate::solver::{Stop, clp};

/// Share of its time limit Clp is given, so that it stops and hands over its duals before
/// the caller's deadline (it counts wall-clock time and checks it at every iteration).
const CLP_SHARE_OF_LIMIT: f64 = 0.9;

/// Seconds the barrier needs on a 1400-face staggered relaxation here (2 cores, 2026), and
/// how that time grows with size, fitted with room to spare to the larger meshes (2591
/// faces: 0.28 s, 3580: 0.37 s, 6589: 1.9 s, 7272: 2.5 s). Regular grids take longer (100 x
/// 100: 29 s, against 6 s expected); the barrier then stops at its time limit.
const SECONDS_AT_1400_FACES: f64 = 0.12;
const TIME_EXPONENT: f64 = 2.0;

/// About how long the barrier needs to converge on a mesh of `faces` faces.
pub(super) fn expected_seconds(faces: usize) -> f64 {
    SECONDS_AT_1400_FACES * (faces as f64 / 1400.0).powf(TIME_EXPONENT)
}

/// The program whose relaxation bounds `bond` on `graph` (the whole program, or one patch's
/// relaxed program), in the compact joint form. Forced pairs are left out: the bound holds
/// for the unrestricted program and so for the restricted one.
fn relaxation(graph: &DualGraph, terms: &Terms<'_>, patch: Option<Patch<'_>>) -> Program {
    let free = vec![true; graph.tiles().len()];
    let fixed = vec![false; graph.tiles().len()];
    let restriction = Restriction {
        free: &free,
        fixed: &fixed,
        patch,
    };
    Program::new(graph, terms, Formulation::Strengthened, &restriction)
}

/// What the barrier proved.
pub(super) struct LinearBound {
    /// `L` at the barrier's last prices: an upper bound on the optimum.
    pub value: f64,
    /// The barrier converged, so `value` is the relaxation's optimum (up to its tolerance).
    pub converged: bool,
}

/// The bound of the relaxation of `bond` (of the whole program, or of one `patch`'s) from
/// Clp's barrier within `time_limit`; `None` when Clp gave nothing in time.
///
/// # Errors
/// [`PatternError::Cancelled`] when `control` asks to stop.
pub(super) fn bound(
    graph: &DualGraph,
    terms: &Terms<'_>,
    patch: Option<Patch<'_>>,
    time_limit: Duration,
    control: &mut Control<'_>,
    progress: impl Fn() -> f64,
) -> Result<Option<LinearBound>, PatternError> {
    let relaxation = relaxation(graph, terms, patch);
    let seconds = time_limit.as_secs_f64() * CLP_SHARE_OF_LIMIT;
    let work = move |stop: Stop| {
        let model = relaxation.model();
        clp::barrier(model, seconds, &stop).map(|duals| LinearBound {
            value: relaxation.constant() + model.dual_bound(&duals.row_duals),
            converged: duals.converged,
        })
    };
    Ok(worker::run(work, time_limit, control, progress)?.flatten())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::cancel_after;
    use crate::mesh::{Topology, generate};
    use crate::pattern::decompose::tests::ragged;
    use crate::pattern::{Bond, Method, PatternOptions, SolveStatus, solve};

    #[test]
    fn any_prices_bound_the_optimum_and_so_do_the_barriers() {
        for mesh in [ragged(7), ragged(8), generate::grid(6, 7)] {
            let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
            for bond in [
                Bond::Staggered { weight: 0.5 },
                Bond::Staggered { weight: 2.0 },
                Bond::RunningBond { weight: 0.5 },
            ] {
                let options = PatternOptions {
                    bond,
                    method: Method::Mip,
                    time_limit: Duration::from_secs(20),
                    ..PatternOptions::default()
                };
                let optimum = solve(&mesh, &options).unwrap();
                assert_eq!(optimum.status, SolveStatus::Optimal);
                let terms = Terms::uniform(&graph, bond);
                let relaxation = relaxation(&graph, &terms, None);
                let model = relaxation.model();
                let rows = model.row_upper.len();
                // Prices of every kind, negative ones included (they count as zero).
                let arbitrary = [
                    vec![0.0; rows],
                    vec![0.5; rows],
                    (0..rows)
                        .map(|r| ((r * 7919) % 13) as f64 / 6.0 - 0.5)
                        .collect(),
                ];
                for prices in arbitrary {
                    let value = model.dual_bound(&prices);
                    assert!(
                        value >= optimum.objective - 1e-9,
                        "{bond:?}: L = {value} < optimum {}",
                        optimum.objective
                    );
                }
                // The barrier's prices, converged or cut short.
                let converged = bound(
                    &graph,
                    &terms,
                    None,
                    Duration::from_secs(20),
                    &mut Control::none(),
                    || 0.0,
                )
                .unwrap()
                .unwrap();
                assert!(converged.converged);
                assert!(converged.value >= optimum.objective - 1e-9);
                let cut_short = clp::barrier(model, 1e-4, &Stop::new()).unwrap();
                assert!(model.dual_bound(&cut_short.row_duals) >= optimum.objective - 1e-9);
            }
        }
    }

    #[test]
    fn the_barrier_stops_on_the_clock_and_on_a_cancel_within_moments() {
        use std::time::Instant;
        // 100 x 100 grid, staggered: the barrier needs many seconds to converge even on a
        // quiet machine (70 x 70 converged within the second on one), each iteration some
        // 60 ms (before the first, some 0.4 s to set up, which it cannot be stopped in).
        let mesh = generate::grid(100, 100);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let terms = Terms::uniform(&graph, Bond::Staggered { weight: 0.5 });
        let relaxation = relaxation(&graph, &terms, None);

        // Clp's limit is wall-clock time: with two threads spinning beside it, the process's
        // processor time runs ahead of the clock, and a limit counted in it would stop the
        // barrier early.
        let spinning = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(true));
        let spinners: Vec<_> = (0..2)
            .map(|_| {
                let spinning = spinning.clone();
                std::thread::spawn(move || {
                    while spinning.load(std::sync::atomic::Ordering::Relaxed) {
                        std::hint::spin_loop();
                    }
                })
            })
            .collect();
        let started = Instant::now();
        let stopped = clp::barrier(relaxation.model(), 1.0, &Stop::new()).unwrap();
        let took = started.elapsed().as_secs_f64();
        spinning.store(false, std::sync::atomic::Ordering::Relaxed);
        spinners.into_iter().for_each(|s| s.join().unwrap());
        assert!(!stopped.converged);
        assert!(
            (1.0..1.6).contains(&took),
            "1 s of wall-clock time took {took:.3} s"
        );

        // A cancel from the caller's callback ends the barrier within moments: one barrier
        // iteration (some 60 ms alone) and the poll. 0.5 s, not less: the other tests of this
        // binary share the two cores, and a clean-clone CI run with a build beside it took
        // 0.28 s (a barrier left running would take the 60 s limit).
        let (mut cancel_after_a_second, asked) = cancel_after(Duration::from_secs(1));
        let mut control = Control::with_progress(&mut cancel_after_a_second);
        let outcome = bound(
            &graph,
            &terms,
            None,
            Duration::from_secs(60),
            &mut control,
            || 0.0,
        );
        let returned = Instant::now();
        assert!(matches!(outcome, Err(PatternError::Cancelled)));
        let after = returned - asked.get().unwrap();
        assert!(
            after < Duration::from_millis(500),
            "returned {after:?} after the cancel"
        );
    }

    /// The whole program's relaxation bound for `bond` on `graph`, with 20 s to converge.
    fn whole_bound(graph: &DualGraph, bond: Bond) -> LinearBound {
        bound(
            graph,
            &Terms::uniform(graph, bond),
            None,
            Duration::from_secs(20),
            &mut Control::none(),
            || 0.0,
        )
        .unwrap()
        .unwrap()
    }

    #[test]
    fn the_relaxation_of_odd_closed_courses_is_their_optimum() {
        // Three rings of seven quads in level courses: three tiles each. Eq. (1) alone
        // lets every tile take one half, 3.5 a ring (10.5); the rings' odd-set rows close it.
        let graph = crate::pattern::program::tests::tube_in_courses(7, 3);
        let found = whole_bound(&graph, Bond::Stack);
        assert!(
            found.converged && (9.0 - 1e-6..9.0 + 1e-6).contains(&found.value),
            "{}",
            found.value
        );
    }

    #[test]
    fn the_star_rows_relaxation_proves_the_papers_figure_5() {
        // 10 x 10, w = 2: 49 tiles and no joint is optimal, one tile short of a perfect
        // matching; the relaxation with the star rows proves it (its optimum rounds to 49).
        let mesh = generate::grid(10, 10);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let found = whole_bound(&graph, Bond::Staggered { weight: 2.0 });
        assert!(
            found.converged && (49.0 - 1e-9..49.5).contains(&found.value),
            "{}",
            found.value
        );
    }
}
