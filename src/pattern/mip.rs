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

/// How CBC searches a program over `graph`: in level courses as for a nearly integral
/// program (no presolve, cuts or heuristics: [`cbc::Search::NearlyIntegral`]), otherwise
/// with CBC's defaults. In courses each face pairs only along its course and the root
/// relaxation is nearly or wholly integral; what is left is where a course's half tile
/// goes, which CBC's first dives settle. Presolve removes little there but cost most of the
/// solve (`match --courses level --method mip`, 2026-12-04, on and off: the 20 m cap's
/// 34,330 faces 21 s and 5.4 s, the same optimum 17014; the 51 programs of the benchmark
/// set 28.2 s and 21.5 s in all, each the same optimum). The cut generators and heuristics
/// then took seconds each on the programs CBC did not prove at its root, and the cuts moved
/// the bound by half a tile at most (`match --courses level`, 2026-12-06, 63 quad meshes of
/// 80-34,219 faces from `run` and `remesh` on the shared surfaces, the shells of
/// `scripts/shells.py` and others, each the same proven optimum: 53.5 s -> 19.0 s in all; a
/// barrel vault with two openings 18.5 -> 2.4 s and, remeshed finer, 17.9 -> 6.6 s, a
/// latitude-longitude hemisphere 6.0 -> 1.5 s, a cone 2.5 -> 0.5 s; the programs solved at
/// the root unchanged, the 20 m cap 6.9 and 6.8 s). Over free programs (either way across
/// every quad) presolve made no consistent difference on the same 51 meshes at 20 s each
/// (752 s and 737 s in all; as many programs proven faster with it as without) and the cuts
/// are what tightens their bound, so CBC's defaults stay.
fn search_for(graph: &DualGraph) -> cbc::Search {
    if graph.in_courses() {
        cbc::Search::NearlyIntegral
    } else {
        cbc::Search::Default
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
    let search = search_for(graph);

    // CBC runs on a worker thread, so that progress callbacks stay on the caller's thread;
    // the caller's cancel and deadline reach it through its stop handlers, which end it
    // within milliseconds wherever it is (in Clp's root linear program too).
    let worker = move |stop: Stop| {
        cbc::solve(program.model(), seconds, gap, search, &stop).map(|solved| {
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
    use crate::control::cancel_after;
    use crate::mesh::{Topology, generate};

    #[test]
    fn programs_in_courses_are_searched_as_nearly_integral_and_reach_the_same_optimum() {
        let mesh = generate::corner_supported_shell(3.0, 0.2);
        let topology = Topology::new(&mesh).unwrap();
        let free_graph = DualGraph::new(&mesh, &topology, &[]);
        assert!(!free_graph.in_courses());
        assert_eq!(search_for(&free_graph), cbc::Search::Default);
        let middle =
            crate::pattern::courses::middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).unwrap();
        // Two openings, so that courses stop and start and the optimum is not the root's.
        let excluded: Vec<bool> = (0..mesh.face_count())
            .map(|f| {
                let c = mesh.face_centroid(f);
                [(0.9, 1.1), (2.0, 1.7)]
                    .iter()
                    .any(|&(x, y)| (c.x - x).hypot(c.y - y) < 0.35)
            })
            .collect();
        for excluded in [vec![], excluded] {
            let graph = DualGraph::restricted(&mesh, &topology, &excluded, Some(&middle));
            assert!(graph.in_courses());
            assert_eq!(search_for(&graph), cbc::Search::NearlyIntegral);
            let all = vec![true; graph.tiles().len()];
            let none = vec![false; graph.tiles().len()];
            let restriction = Restriction {
                free: &all,
                fixed: &none,
                patch: None,
            };
            let terms = Terms::uniform(&graph, crate::pattern::Bond::Staggered { weight: 0.5 });
            let program = Program::new(&graph, &terms, Formulation::Strengthened, &restriction);
            let optimum = |search| {
                let solved = cbc::solve(program.model(), 60.0, 0.0, search, &Stop::new()).unwrap();
                assert_eq!(solved.ending, Ending::Finished, "{search:?}");
                let values = solved.values.unwrap();
                let objective: f64 = values
                    .iter()
                    .zip(&program.model().objective)
                    .map(|(x, c)| x * c)
                    .sum();
                (objective, solved.bound)
            };
            let default = optimum(cbc::Search::Default);
            let integral = optimum(cbc::Search::NearlyIntegral);
            assert!(default.0 > 0.0);
            assert!(
                (default.0 - integral.0).abs() < 1e-6,
                "{default:?} {integral:?}"
            );
            assert!(
                (default.1 - integral.1).abs() < 1e-6,
                "{default:?} {integral:?}"
            );
        }
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
        // 45 x 45 grid: CBC's root linear program alone takes seconds. Cancel 1 s in. The
        // other tests run beside this one on as many threads as there are cores, so a
        // return a scheduler's slice late is tried again (as `at_full_speed` does); a
        // cancel CBC does not hear fails every time.
        let mut late = Vec::new();
        for _ in 0..3 {
            let (mut cancel_after_a_second, asked) = cancel_after(Duration::from_secs(1));
            let mut control = Control::with_progress(&mut cancel_after_a_second);
            let outcome = whole(45, Duration::from_secs(60), &mut control);
            let returned = Instant::now();
            assert!(matches!(outcome, Err(PatternError::Cancelled)));
            let after_cancel = returned - asked.get().unwrap();
            at_full_speed(before).unwrap();
            if after_cancel < Duration::from_millis(200) {
                break;
            }
            late.push(after_cancel);
        }
        assert!(late.len() < 3, "returned {late:?} after the cancel");

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
