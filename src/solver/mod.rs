//! Outgoing bindings to the COIN-OR solvers the pattern stage calls (paper section 3.4:
//! the programs of eqs. 1-3 are solved by an integer solver; their linear relaxations give
//! bounds). This is the only module of the crate that calls out to C; `ffi` holds only our
//! own exports.
//!
//! * [`Model`](crate::solver::Model): a solver-neutral sparse program, `max c.x` subject to
//!   `A x <= b`, `0 <= x <= u`, some columns integer, with `A` stored column by column;
//! * [`cbc`](crate::solver::cbc): CBC's branch and bound on a [`Model`](crate::solver::Model),
//!   written through `good_lp` and solved through its `coin_cbc` backend's raw model, with
//!   our event handlers attached;
//! * [`clp`](crate::solver::clp): Clp's interior-point method through Clp's C interface, for
//!   a model's linear relaxation and its row prices;
//! * [`Stop`](crate::solver::Stop): how a caller stops either of them mid-solve (cancel,
//!   deadline), through CBC's and Clp's event handlers, written in C++ in
//!   `src/solver/watch.cpp` (compiled by build.rs against the linked COIN-OR's headers).
//!
//! `cbc` and `clp` call C, so they alone allow `unsafe` (every block states why it is
//! sound); the rest of the crate denies it.
//!
//! Stages build their programs in their own terms (the pattern stage: `pattern::program`)
//! and hand them over as a [`Model`](crate::solver::Model); nothing here knows of tiles or
//! bonds.

#[allow(unsafe_code)]
pub(crate) mod cbc;
#[allow(unsafe_code)]
pub(crate) mod clp;

use std::ffi::c_int;
use std::sync::Arc;
use std::sync::atomic::{AtomicI32, Ordering};

/// A request to stop a running solver, shared by the thread that watches the caller
/// ([`Control`](crate::control::Control), the deadline) and the thread the solver runs on:
/// CBC and Clp ask it at every node and every iteration (through their event handlers) and
/// return within milliseconds of [`Stop::request`], releasing CBC's process-wide lock.
#[derive(Clone, Debug, Default)]
pub(crate) struct Stop(Arc<AtomicI32>);

impl Stop {
    /// A stop not yet requested.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks the solver to stop as soon as it can.
    pub fn request(&self) {
        self.0.store(1, Ordering::Relaxed);
    }

    /// Whether a stop was requested.
    pub fn requested(&self) -> bool {
        self.0.load(Ordering::Relaxed) != 0
    }

    /// The flag the event handlers read (atomically); it lives as long as this `Stop`.
    fn flag(&self) -> *const c_int {
        self.0.as_ptr().cast_const()
    }
}

/// `max objective.x` subject to `A x <= row_upper` and `0 <= x <= column_upper`, the columns
/// marked `integer` integral, with `A` stored column by column: column `j` has the entries
/// `values[k]` in rows `rows[k]` for `k` in `starts[j]..starts[j + 1]`, rows increasing.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Model {
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
    /// Whether every column is integral (the linear solvers ignore it).
    pub integer: Vec<bool>,
    /// Right-hand side of every row.
    pub row_upper: Vec<f64>,
}

/// One row of a [`Model`] as written: its entries `(column, value)` and its right-hand side.
pub(crate) type Row = (Vec<(usize, f64)>, f64);

impl Model {
    /// The model with these `rows` over columns with this `objective`, upper bounds and
    /// integrality, stored column by column.
    pub fn from_rows(
        rows: &[Row],
        objective: Vec<f64>,
        column_upper: Vec<f64>,
        integer: Vec<bool>,
    ) -> Self {
        let columns = objective.len();
        let mut entries: Vec<Vec<(i32, f64)>> = vec![Vec::new(); columns];
        for (r, (row, _)) in rows.iter().enumerate() {
            let r = i32::try_from(r).unwrap_or(i32::MAX);
            row.iter().for_each(|&(j, a)| entries[j].push((r, a)));
        }
        let mut model = Self {
            starts: vec![0],
            rows: Vec::new(),
            values: Vec::new(),
            objective,
            column_upper,
            integer,
            row_upper: rows.iter().map(|(_, rhs)| *rhs).collect(),
        };
        for column in entries {
            for (r, a) in column {
                model.rows.push(r);
                model.values.push(a);
            }
            model
                .starts
                .push(i32::try_from(model.rows.len()).unwrap_or(i32::MAX));
        }
        model
    }

    /// Number of columns.
    pub fn columns(&self) -> usize {
        self.objective.len()
    }

    /// Entries `(row, value)` of column `j`.
    pub fn column(&self, j: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let entries = self.starts[j] as usize..self.starts[j + 1] as usize;
        entries.map(|k| (self.rows[k] as usize, self.values[k]))
    }

    /// Whether the arrays agree: sizes, column starts increasing from 0 to the entry count,
    /// rows in range and increasing within each column, counts within `int`.
    pub fn is_well_formed(&self) -> bool {
        let columns = self.objective.len();
        let row_count = self.row_upper.len();
        i32::try_from(columns).is_ok()
            && i32::try_from(row_count).is_ok()
            && self.starts.len() == columns + 1
            && self.column_upper.len() == columns
            && self.integer.len() == columns
            && self.rows.len() == self.values.len()
            && self.starts.first() == Some(&0)
            && self.starts.windows(2).all(|w| w[0] <= w[1])
            && self
                .starts
                .last()
                .is_some_and(|&end| usize::try_from(end).ok() == Some(self.rows.len()))
            && self
                .rows
                .iter()
                .all(|&r| usize::try_from(r).is_ok_and(|r| r < row_count))
            && self.starts.windows(2).all(|w| {
                self.rows[w[0] as usize..w[1] as usize]
                    .windows(2)
                    .all(|r| r[0] < r[1])
            })
    }

    /// An upper bound on the optimum of the linear relaxation, and so of the model, from
    /// any prices on the rows (negative ones count as zero), by weak duality:
    /// `L(p) = b.p + sum_j u_j max(0, c_j - A_j.p)`. At the relaxation's optimal prices it is
    /// the relaxation's optimum; whatever the prices, it holds.
    pub fn dual_bound(&self, prices: &[f64]) -> f64 {
        let price = |r: usize| prices.get(r).copied().unwrap_or(0.0).max(0.0);
        let rows: f64 = self
            .row_upper
            .iter()
            .enumerate()
            .map(|(r, b)| b * price(r))
            .sum();
        let columns: f64 = (0..self.columns())
            .map(|j| {
                let priced: f64 = self.column(j).map(|(r, a)| a * price(r)).sum();
                self.column_upper[j] * (self.objective[j] - priced).max(0.0)
            })
            .sum();
        rows + columns
    }
}
