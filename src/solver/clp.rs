//! Clp's interior-point method, imported through Clp's C interface (`Clp_C_Interface.h`),
//! which comes with CBC. CBC's C interface solves linear programs only by the simplex method,
//! which does not check the clock and on the star-row relaxations is 4-10x slower, and it
//! returns no row duals; Clp's barrier stops at a time limit and gives them.
//!
//! The time limit is Clp's barrier iterations asking our event handler (`tp_clp_watch`,
//! `src/solver/watch.cpp`), which counts wall-clock time and also ends the solve within an
//! iteration of a [`Stop`]; Clp's own limit counts the whole process's processor time, which
//! a busy host (Rhino, several threads) spends many times faster than the clock.

use std::ffi::{c_double, c_int, c_void};

use super::{Model, Stop};

/// Clp's opaque model.
#[repr(C)]
struct ClpSimplex {
    _opaque: [u8; 0],
}

#[link(name = "Clp")]
unsafe extern "C" {
    fn Clp_newModel() -> *mut ClpSimplex;
    fn Clp_deleteModel(model: *mut ClpSimplex);
    // `CoinBigIndex` is `int` in the builds distributions ship (COIN_BIG_INDEX 0).
    fn Clp_loadProblem(
        model: *mut ClpSimplex,
        numcols: c_int,
        numrows: c_int,
        start: *const c_int,
        index: *const c_int,
        value: *const c_double,
        collb: *const c_double,
        colub: *const c_double,
        obj: *const c_double,
        rowlb: *const c_double,
        rowub: *const c_double,
    );
    fn Clp_setOptimizationDirection(model: *mut ClpSimplex, value: c_double);
    fn Clp_setLogLevel(model: *mut ClpSimplex, value: c_int);
    fn Clp_initialBarrierNoCrossSolve(model: *mut ClpSimplex) -> c_int;
    fn Clp_status(model: *mut ClpSimplex) -> c_int;
    fn Clp_dualRowSolution(model: *mut ClpSimplex) -> *mut c_double;
}

unsafe extern "C" {
    /// Makes the `Clp_Simplex` (Clp's C interface) stop once `*flag` is non-zero or `seconds`
    /// of wall-clock time have passed (negative: no limit); 0 on success.
    fn tp_clp_watch(model: *mut c_void, flag: *const c_int, seconds: f64) -> c_int;
}

/// What the barrier left: its row duals, and whether it converged.
pub(crate) struct BarrierDuals {
    /// Dual value of every row, as Clp gives them for maximisation.
    pub row_duals: Vec<f64>,
    /// Clp reports an optimum; otherwise the duals are those of its last iterate.
    pub converged: bool,
}

/// Runs Clp's barrier (without crossover: the duals are what is wanted) on the linear
/// relaxation of `program` (its integrality is ignored) for at most about `seconds` of
/// wall-clock time, or until `stop` is requested. `None` when the program is malformed (see
/// [`Model::is_well_formed`]) or the handler cannot be attached.
pub(crate) fn barrier(program: &Model, seconds: f64, stop: &Stop) -> Option<BarrierDuals> {
    if !program.is_well_formed() {
        return None;
    }
    let columns = program.columns();
    let row_count = program.row_upper.len();
    let (Ok(numcols), Ok(numrows)) = (c_int::try_from(columns), c_int::try_from(row_count)) else {
        return None;
    };
    if columns == 0 || row_count == 0 {
        // Nothing for Clp to do: no row needs a price.
        return Some(BarrierDuals {
            row_duals: vec![0.0; row_count],
            converged: true,
        });
    }
    // SAFETY: the model is created, used and deleted here; every array passed has the
    // length Clp reads from it (checked above: `starts` has columns + 1 entries ending at
    // the entry count, every row index is in range, the column and row arrays have
    // `numcols` and `numrows` entries); Clp copies them. A null lower bound means 0 for the
    // columns and minus infinity for the rows. The dual row solution Clp returns has
    // `numrows` entries and lives until the model is deleted; it is copied before that.
    // `tp_clp_watch` attaches a handler (a copy) that reads the flag of `stop`, borrowed for
    // the whole call; it is deleted with the model.
    unsafe {
        let model = Clp_newModel();
        if model.is_null() {
            return None;
        }
        Clp_setLogLevel(model, 0);
        Clp_loadProblem(
            model,
            numcols,
            numrows,
            program.starts.as_ptr(),
            program.rows.as_ptr(),
            program.values.as_ptr(),
            std::ptr::null(),
            program.column_upper.as_ptr(),
            program.objective.as_ptr(),
            std::ptr::null(),
            program.row_upper.as_ptr(),
        );
        Clp_setOptimizationDirection(model, -1.0);
        if tp_clp_watch(model.cast(), stop.flag(), seconds.max(1e-3)) != 0 {
            Clp_deleteModel(model);
            return None;
        }
        Clp_initialBarrierNoCrossSolve(model);
        let converged = Clp_status(model) == 0;
        let duals = Clp_dualRowSolution(model);
        let row_duals = if duals.is_null() {
            vec![0.0; row_count]
        } else {
            std::slice::from_raw_parts(duals, row_count).to_vec()
        };
        Clp_deleteModel(model);
        Some(BarrierDuals {
            row_duals,
            converged,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn malformed_programs_are_refused() {
        let program = |starts: Vec<i32>, rows: Vec<i32>| Model {
            starts,
            rows,
            values: vec![1.0],
            objective: vec![1.0],
            column_upper: vec![2.0],
            integer: vec![false],
            row_upper: vec![1.0],
        };
        // max x, x <= 1, 0 <= x <= 2: the row is binding, its dual is 1.
        assert!(
            barrier(&program(vec![0, 1], vec![0]), 1.0, &Stop::new())
                .is_some_and(|d| d.converged && (d.row_duals[0] - 1.0).abs() < 1e-6)
        );
        assert!(
            barrier(&program(vec![0, 1], vec![1]), 1.0, &Stop::new()).is_none(),
            "row out of range"
        );
        assert!(
            barrier(&program(vec![0, 2], vec![0]), 1.0, &Stop::new()).is_none(),
            "column past the entries"
        );
        assert!(
            barrier(&program(vec![0], vec![0]), 1.0, &Stop::new()).is_none(),
            "starts too short"
        );
        let empty = Model {
            starts: vec![0],
            rows: vec![],
            values: vec![],
            objective: vec![],
            column_upper: vec![],
            integer: vec![],
            row_upper: vec![],
        };
        assert!(
            barrier(&empty, 1.0, &Stop::new())
                .is_some_and(|d| d.converged && d.row_duals.is_empty())
        );
    }
}
