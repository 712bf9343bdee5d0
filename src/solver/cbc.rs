//! CBC's branch and bound on a [`Model`], written through `good_lp` (one `good_lp` variable
//! per column, one `<=` constraint per row, straight from the model's sparse entries) and
//! solved through its `coin_cbc` backend's raw model, to which our event handlers are attached
//! first (`tp_cbc_watch`, `src/solver/watch.cpp`) so that a [`Stop`] ends the solve within
//! milliseconds, wherever CBC is: in its branch and bound, or in Clp's simplex under it (the
//! root linear program, which CBC's own time limit does not reach). `coin_cbc` serialises
//! CBC's calls behind a process-wide lock (CBC is not thread-safe); a stopped solve releases
//! it at once.

use std::ffi::{c_int, c_void};

use coin_cbc::raw::{self, SecondaryStatus, Status};
use good_lp::solvers::coin_cbc::coin_cbc;
use good_lp::{Expression, ProblemVariables, SolverModel, Variable, constraint, variable};

use super::{Model, Stop};

unsafe extern "C" {
    /// Makes the `Cbc_Model` (CBC's C interface) stop once `*flag` is non-zero; 0 on success.
    fn tp_cbc_watch(model: *mut c_void, flag: *const c_int) -> c_int;
}

// `coin_cbc::raw::Model` (0.1.9, pinned in Cargo.toml) holds one field, the `Cbc_Model`
// pointer of CBC's C interface, and exposes it no other way: a struct of one field with the
// size of a pointer has that field at offset 0. These fail to compile if its layout changes.
const _: () = assert!(size_of::<raw::Model>() == size_of::<*mut c_void>());
const _: () = assert!(align_of::<raw::Model>() == align_of::<*mut c_void>());

/// How CBC's search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Ending {
    /// The search finished: the solution is optimal (up to CBC's tolerances).
    Finished,
    /// The time limit stopped it.
    TimeLimit,
    /// The relative gap was reached.
    GapLimit,
    /// CBC declared the model infeasible (with a time limit too short for a first
    /// solution it can say so of a feasible one).
    Infeasible,
    /// A [`Stop`] ended it; what it had is dropped.
    Stopped,
}

/// What CBC returned.
pub(crate) struct Solved {
    /// Value of every column in the best solution found (`None` when infeasible or stopped).
    pub values: Option<Vec<f64>>,
    /// CBC's bound on the optimum (the optimum itself when finished).
    pub bound: f64,
    /// Why the search stopped.
    pub ending: Ending,
}

/// How CBC searches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Search {
    /// CBC's defaults: Clp presolves the root linear program, cut generators tighten its
    /// relaxation and heuristics look for solutions before the search branches.
    Default,
    /// For programs whose root relaxation is nearly or wholly integral (programs over level
    /// courses, see `pattern::mip`): the root is solved as written, with no presolve, cuts
    /// or heuristics, and the search branches at once. There presolve finds little to remove
    /// but costs most of the solve (the 20 m cap's 34,330 faces 21 -> 5 s), the cuts move
    /// the bound by a half tile at most and the heuristics rarely find what the first dives
    /// from the root find anyway, for seconds each (a barrel vault with two openings, 3721
    /// faces: 18.5 -> 2.4 s to the same proven optimum).
    NearlyIntegral,
}

/// Maximises `model` with CBC, stopping after `seconds` of wall-clock time, once the
/// relative gap between its bound and its best solution is at most `gap` (0: prove), or
/// within milliseconds of `stop` being requested, searching as `search` says.
///
/// # Errors
/// A message when the model is malformed or CBC gives up (abandoned, stopped for another
/// reason, unbounded).
pub(crate) fn solve(
    model: &Model,
    seconds: f64,
    gap: f64,
    search: Search,
    stop: &Stop,
) -> Result<Solved, String> {
    if !model.is_well_formed() {
        return Err("malformed model".into());
    }
    let mut variables = ProblemVariables::new();
    let columns: Vec<Variable> = (0..model.columns())
        .map(|j| {
            let column = variable().min(0.0).max(model.column_upper[j]);
            variables.add(if model.integer[j] {
                column.integer()
            } else {
                column
            })
        })
        .collect();
    let mut objective = Expression::with_capacity(model.columns());
    for (&column, &c) in columns.iter().zip(&model.objective) {
        if c != 0.0 {
            objective.add_mul(c, column);
        }
    }
    // The model is stored column by column; constraints are written row by row.
    let mut rows: Vec<Expression> = vec![Expression::default(); model.row_upper.len()];
    for (j, &column) in columns.iter().enumerate() {
        for (r, a) in model.column(j) {
            rows[r].add_mul(a, column);
        }
    }
    let mut problem = variables.maximise(objective).using(coin_cbc);
    problem.set_parameter("log", "0");
    problem.set_parameter("slog", "0");
    problem.set_parameter("timeMode", "elapsed");
    problem.set_parameter("sec", &format!("{:.3}", seconds.max(0.001)));
    if search == Search::NearlyIntegral {
        problem.set_parameter("presolve", "off");
        problem.set_parameter("cuts", "off");
        problem.set_parameter("heuristicsOnOff", "off");
    }
    if gap > 0.0 {
        problem.set_parameter("ratioGap", &format!("{gap}"));
    }
    for (row, &upper) in rows.into_iter().zip(&model.row_upper) {
        problem.add_constraint(constraint::leq(row, upper));
    }
    // good_lp's `solve` would build this raw model and solve it at once; it is built here
    // instead (the same model: good_lp adds column j for variable j, in order) so that the
    // handlers go in before CBC starts.
    let mut cbc = problem.as_inner().to_raw();
    // SAFETY: `cbc` is a `raw::Model` whose only field is its `*mut Cbc_Model` (asserted
    // above by size and alignment), so its first pointer-sized bytes are that pointer, valid
    // until `cbc` is dropped. `tp_cbc_watch` attaches handlers (copies) that read the flag of
    // `stop`, which this function keeps alive (borrowed) until after `solve` returns; the
    // model and its handlers are deleted together when `cbc` is dropped, and CBC calls them
    // only during `solve`.
    let watched = unsafe {
        let pointer = std::ptr::from_ref(&cbc).cast::<*mut c_void>().read();
        tp_cbc_watch(pointer, stop.flag())
    };
    if watched != 0 {
        return Err("cannot attach the stop handlers to CBC".into());
    }
    cbc.solve();
    if stop.requested() {
        return Ok(Solved {
            values: None,
            bound: f64::INFINITY,
            ending: Ending::Stopped,
        });
    }
    let values = || Some(cbc.col_solution().to_vec());
    let bound = cbc.best_possible_value();
    let ending = match cbc.status() {
        Status::Stopped if cbc.secondary_status() == SecondaryStatus::StoppedOnTime => {
            Ending::TimeLimit
        }
        Status::Stopped => return Err("CBC stopped".into()),
        Status::Abandoned => return Err("CBC gave up: Abandoned".into()),
        Status::UserEvent => return Err("CBC gave up: UserEvent".into()),
        Status::Finished | Status::Unlaunched => {
            if cbc.is_continuous_unbounded() {
                return Err("the model is unbounded".into());
            }
            if cbc.is_proven_infeasible() {
                return Ok(Solved {
                    values: None,
                    bound: f64::INFINITY,
                    ending: Ending::Infeasible,
                });
            }
            match cbc.secondary_status() {
                SecondaryStatus::StoppedOnTime => Ending::TimeLimit,
                SecondaryStatus::StoppedOnGap => Ending::GapLimit,
                _ => Ending::Finished,
            }
        }
    };
    Ok(Solved {
        values: values(),
        bound,
        ending,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_small_integer_program_is_solved_and_a_malformed_one_refused() {
        // max x + y, x + y <= 1.5, x, y binary: optimum 1.
        let model = Model::from_rows(
            &[(vec![(0, 1.0), (1, 1.0)], 1.5)],
            vec![1.0, 1.0],
            vec![1.0, 1.0],
            vec![true, true],
        );
        for search in [Search::Default, Search::NearlyIntegral] {
            let solved = solve(&model, 10.0, 0.0, search, &Stop::new()).unwrap();
            assert_eq!(solved.ending, Ending::Finished);
            assert!((solved.bound - 1.0).abs() < 1e-6, "{search:?}");
            let values = solved.values.unwrap();
            assert!(
                (values.iter().sum::<f64>() - 1.0).abs() < 1e-9,
                "{search:?}: {values:?}"
            );
        }
        let broken = Model {
            rows: vec![3, 0],
            ..model
        };
        assert!(solve(&broken, 10.0, 0.0, Search::Default, &Stop::new()).is_err());
    }
}
