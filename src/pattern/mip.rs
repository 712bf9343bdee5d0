//! The paper's binary integer programs (eqs. 1-3, written in `program`) solved with CBC
//! (`solver::cbc`), on the whole dual graph, on a window of it with the rest of the pattern
//! held fixed, or as one patch's relaxation.

use std::time::Duration;

use super::program::{Program, Restriction};
use super::{DualGraph, Formulation, PatternError, Terms, worker};
use crate::control::Control;
use crate::solver::Stop;
use crate::solver::cbc::{self, Ending};

/// CBC gets this share of the time limit, so that it can stop and hand over its incumbent
/// before the caller's deadline.
const CBC_SHARE_OF_LIMIT: f64 = 0.9;

/// What CBC returned.
pub(super) struct Outcome {
    /// `free` tiles chosen by the best solution found, or `None` when CBC returned none.
    pub chosen: Option<Vec<bool>>,
    /// Proven upper bound on the objective of the whole pattern (fixed tiles included); the
    /// optimum itself when CBC finished its search.
    pub bound: f64,
    /// The search stopped on the time limit.
    pub timed_out: bool,
}

/// Seconds Clp's simplex method takes for the linear relaxation of a 1000-face staggered
/// program here (2 cores, 2026; 300 faces: 0.05 s, 1399 faces: 2.9 s), the root of CBC's
/// search, and how that time grows with size.
const LINEAR_SECONDS_AT_1000_FACES: f64 = 1.0;
const LINEAR_TIME_EXPONENT: f64 = 2.5;

/// About how long CBC's root linear program takes on a program over `faces` faces. A solve
/// stopped by its deadline before its root is solved gives neither a pattern nor a bound, so
/// the engine starts none it does not expect to get past it in time.
pub(super) fn expected_linear_seconds(faces: usize) -> f64 {
    LINEAR_SECONDS_AT_1000_FACES * (faces as f64 / 1000.0).powf(LINEAR_TIME_EXPONENT)
}

/// Clp's presolve for the root of a program over `graph`: off in level courses, on
/// otherwise. In courses the root relaxation is nearly or wholly integral and presolve
/// removes little but costs most of the solve (`match --courses level --method mip`,
/// 2026-12-04, on and off: the 20 m cap's 34,330 faces 21 s and 5.4 s, the same optimum
/// 17014; the 51 programs of the benchmark set 28.2 s and 21.5 s in all, each the same
/// optimum). Over free programs (either way across every quad) it made no consistent
/// difference on the same 51 meshes at 20 s each (752 s and 737 s in all; as many
/// programs proven faster with it as without), so CBC's default stays.
fn presolve_for(graph: &DualGraph) -> cbc::Presolve {
    if graph.in_courses() {
        cbc::Presolve::Off
    } else {
        cbc::Presolve::On
    }
}

/// Solves the bond's program over the free tiles of `restriction`, stopping at the time
/// limit or once CBC's relative gap is at most `gap` (0: prove optimality).
#[expect(
    clippy::too_many_arguments,
    reason = "the program's inputs, its limits and its control"
)]
pub(super) fn solve(
    graph: &DualGraph,
    terms: &Terms<'_>,
    formulation: Formulation,
    restriction: &Restriction<'_>,
    time_limit: Duration,
    gap: f64,
    control: &mut Control<'_>,
    progress: impl Fn() -> f64,
) -> Result<Outcome, PatternError> {
    let program = Program::new(graph, terms, formulation, restriction);
    let constant = program.constant();
    if program.model().columns() == 0 {
        return Ok(Outcome {
            chosen: Some(vec![false; graph.tiles().len()]),
            bound: constant,
            timed_out: false,
        });
    }
    let seconds = time_limit.as_secs_f64() * CBC_SHARE_OF_LIMIT;
    let presolve = presolve_for(graph);

    // CBC runs on a worker thread, so that progress callbacks stay on the caller's thread;
    // the caller's cancel and deadline reach it through its stop handlers, which end it
    // within milliseconds wherever it is (in Clp's root linear program too).
    let worker = move |stop: Stop| {
        cbc::solve(program.model(), seconds, gap, presolve, &stop).map(|solved| {
            let chosen = solved.values.map(|values| program.chosen(&values));
            (chosen, solved.bound, solved.ending)
        })
    };
    let Some(result) = worker::run(worker, time_limit, control, progress)? else {
        return Ok(Outcome {
            chosen: None,
            bound: f64::INFINITY,
            timed_out: true,
        });
    };
    let (chosen, bound, ending) = result.map_err(PatternError::Solver)?;
    // CBC stopped by its time limit before it had a solution may call the problem
    // infeasible; every program here is feasible (no tiles at all). A stopped CBC (the
    // worker's deadline came first) has nothing to give.
    if matches!(ending, Ending::Infeasible | Ending::Stopped) {
        return Ok(Outcome {
            chosen: None,
            bound: f64::INFINITY,
            timed_out: true,
        });
    }
    Ok(Outcome {
        chosen,
        bound: if bound.is_finite() {
            bound + constant
        } else {
            f64::INFINITY
        },
        timed_out: ending == Ending::TimeLimit,
    })
}

#[cfg(test)]
mod tests {
    use std::time::Instant;

    use super::*;
    use crate::mesh::{Topology, generate};

    #[test]
    fn programs_in_courses_skip_clps_presolve_and_reach_the_same_optimum() {
        let mesh = generate::corner_supported_shell(3.0, 0.4);
        let topology = Topology::new(&mesh).unwrap();
        let free_graph = DualGraph::new(&mesh, &topology, &[]);
        assert!(!free_graph.in_courses());
        assert_eq!(presolve_for(&free_graph), cbc::Presolve::On);
        let middle =
            crate::pattern::courses::middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).unwrap();
        let graph = DualGraph::restricted(&mesh, &topology, &[], Some(&middle));
        assert!(graph.in_courses());
        assert_eq!(presolve_for(&graph), cbc::Presolve::Off);
        let all = vec![true; graph.tiles().len()];
        let none = vec![false; graph.tiles().len()];
        let restriction = Restriction {
            free: &all,
            fixed: &none,
            patch: None,
        };
        let terms = Terms::uniform(&graph, crate::pattern::Bond::Staggered { weight: 0.5 });
        let program = Program::new(&graph, &terms, Formulation::Strengthened, &restriction);
        let optimum = |presolve| {
            let solved = cbc::solve(program.model(), 60.0, 0.0, presolve, &Stop::new()).unwrap();
            assert_eq!(solved.ending, Ending::Finished, "{presolve:?}");
            let values = solved.values.unwrap();
            let objective: f64 = values
                .iter()
                .zip(&program.model().objective)
                .map(|(x, c)| x * c)
                .sum();
            (objective, solved.bound)
        };
        let (with, without) = (optimum(cbc::Presolve::On), optimum(cbc::Presolve::Off));
        assert!(with.0 > 0.0);
        assert!((with.0 - without.0).abs() < 1e-6, "{with:?} {without:?}");
        assert!((with.1 - without.1).abs() < 1e-6, "{with:?} {without:?}");
    }

    /// The whole program of an `n` x `n` grid, staggered, on CBC for at most `limit`.
    fn whole(
        n: usize,
        limit: Duration,
        control: &mut Control<'_>,
    ) -> Result<Outcome, PatternError> {
        let mesh = generate::grid(n, n);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let free = vec![true; graph.tiles().len()];
        let fixed = vec![false; graph.tiles().len()];
        let restriction = Restriction {
            free: &free,
            fixed: &fixed,
            patch: None,
        };
        let terms = Terms::uniform(&graph, crate::pattern::Bond::Staggered { weight: 0.5 });
        solve(
            &graph,
            &terms,
            Formulation::Strengthened,
            &restriction,
            limit,
            0.0,
            control,
            || 0.0,
        )
    }

    /// Seconds CBC takes to prove a 12 x 12 grid.
    fn small() -> f64 {
        let started = Instant::now();
        let outcome = whole(12, Duration::from_secs(60), &mut Control::none()).unwrap();
        assert!(outcome.chosen.is_some() && !outcome.timed_out);
        started.elapsed().as_secs_f64()
    }

    /// Whether a 12 x 12 grid is proven about as fast as `before` (in seconds) once more. Other
    /// tests of this process solve with CBC at the same time and may hold its lock for a
    /// while, so it is given five tries: a solve stopped earlier and still holding the lock
    /// would fail all of them.
    fn at_full_speed(before: f64) -> Result<(), String> {
        let mut tries = Vec::new();
        for _ in 0..5 {
            let after = small();
            if after < 2.0 * before + 0.25 {
                return Ok(());
            }
            tries.push(format!("{after:.3}"));
        }
        Err(format!("{} s, {before:.3} s before", tries.join(", ")))
    }

    #[test]
    fn a_cancel_or_the_deadline_inside_cbc_stops_it_and_leaves_it_free() {
        let before = small();
        // 45 x 45 grid: CBC's root linear program alone takes seconds. Cancel 1 s in.
        let started = Instant::now();
        let mut asked: Option<Instant> = None;
        let mut cancel_after_a_second = |_: f64| {
            if started.elapsed() < Duration::from_secs(1) {
                return true;
            }
            asked.get_or_insert_with(Instant::now);
            false
        };
        let mut control = Control::with_progress(&mut cancel_after_a_second);
        let outcome = whole(45, Duration::from_secs(60), &mut control);
        let returned = Instant::now();
        assert!(matches!(outcome, Err(PatternError::Cancelled)));
        let after_cancel = returned - asked.unwrap();
        assert!(
            after_cancel < Duration::from_millis(200),
            "returned {after_cancel:?} after the cancel"
        );
        at_full_speed(before).unwrap();

        // The deadline, inside the root linear program, stops CBC the same way.
        let started = Instant::now();
        let outcome = whole(45, Duration::from_secs(1), &mut Control::none()).unwrap();
        let took = started.elapsed().as_secs_f64();
        assert!(
            outcome.timed_out && outcome.chosen.is_none() && took < 1.5,
            "{took:.3} s"
        );
        at_full_speed(before).unwrap();
    }
}
