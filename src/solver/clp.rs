//! Clp's interior-point method, imported through Clp's C interface (`Clp_C_Interface.h`),
//! which comes with CBC. CBC's C interface solves linear programs only by the simplex method,
//! which does not check the clock and on the star-row relaxations is 4-10x slower, and it
//! returns no row duals; Clp's barrier stops at a time limit and gives them.

use std::ffi::{c_double, c_int};

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
    fn Clp_setMaximumSeconds(model: *mut ClpSimplex, value: c_double);
    fn Clp_initialBarrierNoCrossSolve(model: *mut ClpSimplex) -> c_int;
    fn Clp_status(model: *mut ClpSimplex) -> c_int;
    fn Clp_dualRowSolution(model: *mut ClpSimplex) -> *mut c_double;
}

/// `max objective.x` subject to `A x <= row_upper` and `0 <= x <= column_upper`, with `A`
/// stored column by column: column `j` has the entries `values[k]` in rows `rows[k]` for
/// `k` in `starts[j]..starts[j + 1]`.
pub(crate) struct LinearProgram {
    /// Start of every column's entries, and their end.
    pub starts: Vec<i32>,
    /// Row of every entry.
    pub rows: Vec<i32>,
    /// Value of every entry.
    pub values: Vec<f64>,
    /// Objective of every column.
    pub objective: Vec<f64>,
    /// Upper bound of every column.
    pub column_upper: Vec<f64>,
    /// Right-hand side of every row.
    pub row_upper: Vec<f64>,
}

/// What the barrier left: its row duals, and whether it converged.
pub(crate) struct BarrierDuals {
    /// Dual value of every row, as Clp gives them for maximisation.
    pub row_duals: Vec<f64>,
    /// Clp reports an optimum; otherwise the duals are those of its last iterate.
    pub converged: bool,
}

/// Runs Clp's barrier (without crossover: the duals are what is wanted) on `program` for at
/// most about `seconds` of processor time. `None` when the program is malformed (sizes or
/// indices inconsistent, a count beyond `int`).
pub(crate) fn barrier(program: &LinearProgram, seconds: f64) -> Option<BarrierDuals> {
    let columns = program.objective.len();
    let row_count = program.row_upper.len();
    let well_formed = program.starts.len() == columns + 1
        && program.column_upper.len() == columns
        && program.rows.len() == program.values.len()
        && program.starts.first() == Some(&0)
        && program.starts.windows(2).all(|w| w[0] <= w[1])
        && program
            .starts
            .last()
            .is_some_and(|&end| usize::try_from(end).ok() == Some(program.rows.len()))
        && program
            .rows
            .iter()
            .all(|&r| usize::try_from(r).is_ok_and(|r| r < row_count));
    let (Ok(numcols), Ok(numrows)) = (c_int::try_from(columns), c_int::try_from(row_count)) else {
        return None;
    };
    if !well_formed {
        return None;
    }
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
        Clp_setMaximumSeconds(model, seconds.max(1e-3));
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
