//! CBC's branch and bound on a [`Model`], through the `coin_cbc` crate's raw model (one
//! `Cbc_loadProblem` of the column-major arrays: no expression building on the way).
//! `coin_cbc` serialises CBC's calls behind a process-wide lock (CBC is not thread-safe).

use std::ffi::CString;

use coin_cbc::raw::{Model as Cbc, SecondaryStatus, Sense, Status};

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
    let mut cbc = Cbc::new();
    cbc.load_problem(
        model.columns(),
        model.row_upper.len(),
        &model.starts,
        &model.rows,
        &model.values,
        None,
        Some(&model.column_upper),
        Some(&model.objective),
        None,
        Some(&model.row_upper),
    );
    for (j, _) in model.integer.iter().enumerate().filter(|(_, i)| **i) {
        cbc.set_integer(j);
    }
    cbc.set_obj_sense(Sense::Maximize);
    let mut set = |name: &str, value: String| {
        let (Ok(name), Ok(value)) = (CString::new(name), CString::new(value)) else {
            return;
        };
        cbc.set_parameter(&name, &value);
    };
    set("log", "0".into());
    set("slog", "0".into());
    set("timeMode", "elapsed".into());
    set("sec", format!("{:.3}", seconds.max(0.001)));
    if gap > 0.0 {
        set("ratioGap", format!("{gap}"));
    }
    cbc.solve();
    let finished = |cbc: &Cbc| match cbc.secondary_status() {
        SecondaryStatus::StoppedOnTime => Ending::TimeLimit,
        SecondaryStatus::StoppedOnGap => Ending::GapLimit,
        _ => Ending::Finished,
    };
    let ending = match cbc.status() {
        Status::Stopped if cbc.secondary_status() == SecondaryStatus::StoppedOnTime => {
            Ending::TimeLimit
        }
        Status::Stopped => return Err("CBC stopped".into()),
        Status::Abandoned => return Err("CBC abandoned the search".into()),
        Status::UserEvent => return Err("CBC stopped on a user event".into()),
        Status::Finished | Status::Unlaunched if cbc.is_continuous_unbounded() => {
            return Err("the model is unbounded".into());
        }
        Status::Finished | Status::Unlaunched if cbc.is_proven_infeasible() => Ending::Infeasible,
        Status::Finished | Status::Unlaunched => finished(&cbc),
    };
    Ok(Solved {
        values: (ending != Ending::Infeasible).then(|| cbc.col_solution().to_vec()),
        bound: cbc.best_possible_value(),
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
