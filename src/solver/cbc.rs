//! CBC's branch and bound on a [`Model`], through `good_lp` and its `coin_cbc` backend: one
//! `good_lp` variable per column, one `<=` constraint per row, written straight from the
//! model's sparse entries. `coin_cbc` serialises CBC's calls behind a process-wide lock (CBC
//! is not thread-safe).

use good_lp::solvers::coin_cbc::coin_cbc;
use good_lp::{
    Expression, ProblemVariables, ResolutionError, Solution, SolutionStatus, SolverModel, Variable,
    constraint, variable,
};

use super::Model;

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
}

/// What CBC returned.
pub(crate) struct Solved {
    /// Value of every column in the best solution found (`None` when infeasible).
    pub values: Option<Vec<f64>>,
    /// CBC's bound on the optimum (the optimum itself when finished).
    pub bound: f64,
    /// Why the search stopped.
    pub ending: Ending,
}

/// Maximises `model` with CBC, stopping after `seconds` of wall-clock time, or once the
/// relative gap between its bound and its best solution is at most `gap` (0: prove).
///
/// # Errors
/// A message when the model is malformed or CBC gives up (abandoned, stopped for another
/// reason, unbounded).
pub(crate) fn solve(model: &Model, seconds: f64, gap: f64) -> Result<Solved, String> {
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
    if gap > 0.0 {
        problem.set_parameter("ratioGap", &format!("{gap}"));
    }
    for (row, &upper) in rows.into_iter().zip(&model.row_upper) {
        problem.add_constraint(constraint::leq(row, upper));
    }
    match problem.solve() {
        Ok(solution) => {
            let ending = match solution.status() {
                SolutionStatus::TimeLimit => Ending::TimeLimit,
                SolutionStatus::GapLimit => Ending::GapLimit,
                SolutionStatus::Optimal => Ending::Finished,
            };
            Ok(Solved {
                values: Some(columns.iter().map(|&v| solution.value(v)).collect()),
                bound: solution.model().best_possible_value(),
                ending,
            })
        }
        Err(ResolutionError::Infeasible) => Ok(Solved {
            values: None,
            bound: f64::INFINITY,
            ending: Ending::Infeasible,
        }),
        Err(ResolutionError::Unbounded) => Err("the model is unbounded".into()),
        Err(other) => Err(format!("CBC gave up: {other}")),
    }
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
        let solved = solve(&model, 10.0, 0.0).unwrap();
        assert_eq!(solved.ending, Ending::Finished);
        let values = solved.values.unwrap();
        assert!(
            (values.iter().sum::<f64>() - 1.0).abs() < 1e-9,
            "{values:?}"
        );
        assert!((solved.bound - 1.0).abs() < 1e-6);
        let broken = Model {
            rows: vec![3, 0],
            ..model
        };
        assert!(solve(&broken, 10.0, 0.0).is_err());
    }
}
