//! Bound from the linear relaxation of the whole program (eqs. 1-3, with the star rows for
//! eq. 2), or of one patch's relaxed program (see `decompose`), solved by Clp's
//! interior-point method.
//!
//! For the relaxation `max c.x` subject to `A x <= b` and `0 <= x <= 1`, any prices `p >= 0`
//! on the rows bound the optimum, and so the integer optimum (weak duality):
//! `L(p) = b.p + sum_j max(0, c_j - A_j.p)`. The bound is computed here from the prices the
//! barrier leaves, whether it converged or the time limit stopped it, so it holds whatever
//! the solver's tolerances and status; at convergence it is the relaxation's optimum.
//!
//! With the star rows this optimum is within a few tiles of the integer optimum on meshes
//! whose singularities and ragged boundaries force defects (the QuadriFlow hypar: 691.51
//! against 688.5 found), where a patch decomposition has to cut across the seams that join
//! them; and the barrier reaches it in a fraction of the simplex method's time (0.12 s
//! against 2.4 s there), on a program written with one joint column per regular vertex.

use std::collections::HashMap;
use std::time::Duration;

use super::mip::Patch;
use super::{Bond, DualGraph, PatternError, worker};
use crate::control::Control;
use crate::solver::clp::{self, LinearProgram};

/// Share of its time limit Clp is given, so that it stops and hands over its duals before
/// the caller's deadline (it counts processor time and checks it between iterations).
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

/// The relaxation as Clp takes it: a column per tile, per regular vertex's joints (eq. 2
/// with the star rows) and per other pair of the bond's relation (eq. 2's y, eq. 3's z).
pub(super) struct Relaxation {
    program: LinearProgram,
}

impl Relaxation {
    /// The relaxation of `bond` on `graph`, or of one patch's relaxed program (see
    /// [`Patch`]: only its faces constrained, each worth half a tile when covered, only the
    /// bond pairs it owns counted). Forced pairs are left out: the bound holds for the
    /// unrestricted program and so for the restricted one.
    pub fn new(graph: &DualGraph, bond: Bond, patch: Option<Patch<'_>>) -> Self {
        let tiles = graph.tiles();
        let (relation, per_pair) = graph.bond_pairs(bond);
        let counted = |f: usize| patch.is_none_or(|p| p.faces[f]);
        let owned = |i: usize| patch.is_none_or(|p| p.owned[i]);
        // A column for every tile with a face in the patch, worth half a tile per such face.
        let mut objective = Vec::new();
        let mut tile_column = vec![None; tiles.len()];
        for (t, tile) in tiles.iter().enumerate() {
            let inside = tile.faces.iter().filter(|&&f| counted(f)).count();
            if inside > 0 {
                tile_column[t] = Some(objective.len());
                objective.push(0.5 * inside as f64);
            }
        }
        let mut rows: Vec<(Vec<(usize, f64)>, f64)> = Vec::new();
        // Eq. (1): each face in at most one tile.
        for f in (0..graph.face_count()).filter(|&f| counted(f) && !graph.face_tiles(f).is_empty())
        {
            rows.push((
                graph
                    .face_tiles(f)
                    .iter()
                    .filter_map(|&t| tile_column[t])
                    .map(|j| (j, 1.0))
                    .collect(),
                1.0,
            ));
        }
        // Eq. (2) with the star rows (see `Formulation::Strengthened`) at a regular vertex
        // whose four tiles lie in the patch and whose two joints are both counted: the
        // joints' y appear in no other row, and the set {y_ac, y_bd in [0, 1] : y_ac >= x_a +
        // x_c - 1, y_bd >= x_b + x_d - 1, y_ac + y_bd >= x_a + x_b + x_c + x_d - 1} projects
        // onto s = y_ac + y_bd as exactly s >= x_a + x_b + x_c + x_d - 1, s >= 0 (the face
        // rows keep the sum of the four x at most 2). So one column s, costing w, and one
        // row stand for two columns and three rows, with the same optimum; for integer x, s
        // is the number of joints at the vertex. The barrier's time falls with the size.
        let counted_pair =
            |i: usize| owned(i) && relation[i].iter().all(|&t| tile_column[t].is_some());
        let mut starred = vec![false; relation.len()];
        if let Bond::Staggered { .. } = bond {
            let index_of: HashMap<[usize; 2], usize> = relation
                .iter()
                .enumerate()
                .map(|(i, &pair)| (pair, i))
                .collect();
            let joint = |a: usize, b: usize| {
                index_of
                    .get(&[a.min(b), a.max(b)])
                    .copied()
                    .filter(|&i| counted_pair(i))
            };
            let inside = |t: usize| tiles[t].faces.iter().all(|&f| counted(f));
            for &star in graph
                .regular_vertex_stars()
                .iter()
                .filter(|star| star.iter().all(|&t| inside(t)))
            {
                let [a, b, c, d] = star;
                // Every joint belongs to one vertex; were one shared, counting it at two
                // vertices would overstate its cost, so such a star is left out.
                if let (Some(ac), Some(bd)) = (joint(a, c), joint(b, d))
                    && !starred[ac]
                    && !starred[bd]
                {
                    starred[ac] = true;
                    starred[bd] = true;
                    let joints = objective.len();
                    objective.push(per_pair);
                    let mut row: Vec<(usize, f64)> = star
                        .iter()
                        .filter_map(|&t| tile_column[t])
                        .map(|x| (x, 1.0))
                        .collect();
                    row.push((joints, -1.0));
                    rows.push((row, 1.0));
                }
            }
        }
        for &[a, b] in relation
            .iter()
            .enumerate()
            .filter(|&(i, _)| owned(i) && !starred[i])
            .map(|(_, pair)| pair)
        {
            match (tile_column[a], tile_column[b]) {
                (Some(xa), Some(xb)) => {
                    let pair = objective.len();
                    objective.push(per_pair);
                    match bond {
                        Bond::Stack => {}
                        // Eq. (2): y >= x_a + x_b - 1.
                        Bond::Staggered { .. } => {
                            rows.push((vec![(xa, 1.0), (xb, 1.0), (pair, -1.0)], 1.0))
                        }
                        // Eq. (3): z <= x_a and z <= x_b.
                        Bond::RunningBond { .. } => {
                            rows.push((vec![(pair, 1.0), (xa, -1.0)], 0.0));
                            rows.push((vec![(pair, 1.0), (xb, -1.0)], 0.0));
                        }
                    }
                }
                // A penalty pair with a tile outside the patch is left out, which can only
                // raise the bound; a reward pair is bounded by its tile in the patch alone.
                (Some(x), None) | (None, Some(x)) if per_pair > 0.0 => objective[x] += per_pair,
                _ => {}
            }
        }
        Self {
            program: column_major(&rows, objective),
        }
    }

    /// `L(prices)`: an upper bound on the relaxation's optimum for any prices, negative ones
    /// counting as zero.
    pub fn bound(&self, prices: &[f64]) -> f64 {
        let program = &self.program;
        let price = |r: i32| prices[r as usize].max(0.0);
        let rows: f64 = program
            .row_upper
            .iter()
            .zip(prices)
            .map(|(b, p)| b * p.max(0.0))
            .sum();
        let columns: f64 = (0..program.objective.len())
            .map(|j| {
                let entries = program.starts[j] as usize..program.starts[j + 1] as usize;
                let priced: f64 = entries
                    .map(|k| program.values[k] * price(program.rows[k]))
                    .sum();
                program.column_upper[j] * (program.objective[j] - priced).max(0.0)
            })
            .sum();
        rows + columns
    }
}

/// The program with these rows (entries `(column, value)` and right-hand side) and columns
/// in `[0, 1]`, stored column by column as Clp takes it.
fn column_major(rows: &[(Vec<(usize, f64)>, f64)], objective: Vec<f64>) -> LinearProgram {
    let columns = objective.len();
    let mut entries: Vec<Vec<(i32, f64)>> = vec![Vec::new(); columns];
    for (r, (row, _)) in rows.iter().enumerate() {
        let r = i32::try_from(r).unwrap_or(i32::MAX);
        row.iter().for_each(|&(j, a)| entries[j].push((r, a)));
    }
    let mut program = LinearProgram {
        starts: vec![0],
        rows: Vec::new(),
        values: Vec::new(),
        objective,
        column_upper: vec![1.0; columns],
        row_upper: rows.iter().map(|(_, rhs)| *rhs).collect(),
    };
    for column in entries {
        for (r, a) in column {
            program.rows.push(r);
            program.values.push(a);
        }
        program
            .starts
            .push(i32::try_from(program.rows.len()).unwrap_or(i32::MAX));
    }
    program
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
    bond: Bond,
    patch: Option<Patch<'_>>,
    time_limit: Duration,
    control: &mut Control<'_>,
    progress: impl Fn() -> f64,
) -> Result<Option<LinearBound>, PatternError> {
    let relaxation = Relaxation::new(graph, bond, patch);
    let seconds = time_limit.as_secs_f64() * CLP_SHARE_OF_LIMIT;
    let work = move || {
        clp::barrier(&relaxation.program, seconds).map(|duals| LinearBound {
            value: relaxation.bound(&duals.row_duals),
            converged: duals.converged,
        })
    };
    Ok(worker::run(work, time_limit, control, progress)?.flatten())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Topology, generate};
    use crate::pattern::decompose::tests::ragged;
    use crate::pattern::{Method, PatternOptions, SolveStatus, solve};

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
                let relaxation = Relaxation::new(&graph, bond, None);
                let rows = relaxation.program.row_upper.len();
                // Prices of every kind, negative ones included (they count as zero).
                let arbitrary = [
                    vec![0.0; rows],
                    vec![0.5; rows],
                    (0..rows)
                        .map(|r| ((r * 7919) % 13) as f64 / 6.0 - 0.5)
                        .collect(),
                ];
                for prices in arbitrary {
                    let value = relaxation.bound(&prices);
                    assert!(
                        value >= optimum.objective - 1e-9,
                        "{bond:?}: L = {value} < optimum {}",
                        optimum.objective
                    );
                }
                // The barrier's prices, converged or cut short.
                let converged = bound(
                    &graph,
                    bond,
                    None,
                    Duration::from_secs(20),
                    &mut Control::none(),
                    || 0.0,
                )
                .unwrap()
                .unwrap();
                assert!(converged.converged);
                assert!(converged.value >= optimum.objective - 1e-9);
                let cut_short = clp::barrier(&relaxation.program, 1e-4).unwrap();
                assert!(relaxation.bound(&cut_short.row_duals) >= optimum.objective - 1e-9);
            }
        }
    }

    #[test]
    fn the_star_rows_relaxation_proves_the_papers_figure_5() {
        // 10 x 10, w = 2: 49 tiles and no joint is optimal, one tile short of a perfect
        // matching; the relaxation with the star rows proves it (its optimum rounds to 49).
        let mesh = generate::grid(10, 10);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let found = bound(
            &graph,
            Bond::Staggered { weight: 2.0 },
            None,
            Duration::from_secs(20),
            &mut Control::none(),
            || 0.0,
        )
        .unwrap()
        .unwrap();
        assert!(
            found.converged && (49.0 - 1e-9..49.5).contains(&found.value),
            "{}",
            found.value
        );
    }

    #[test]
    fn malformed_programs_are_refused() {
        let program = |starts: Vec<i32>, rows: Vec<i32>| LinearProgram {
            starts,
            rows,
            values: vec![1.0],
            objective: vec![1.0],
            column_upper: vec![2.0],
            row_upper: vec![1.0],
        };
        // max x, x <= 1, 0 <= x <= 2: the row is binding, its dual is 1.
        assert!(
            clp::barrier(&program(vec![0, 1], vec![0]), 1.0)
                .is_some_and(|d| d.converged && (d.row_duals[0] - 1.0).abs() < 1e-6)
        );
        assert!(
            clp::barrier(&program(vec![0, 1], vec![1]), 1.0).is_none(),
            "row out of range"
        );
        assert!(
            clp::barrier(&program(vec![0, 2], vec![0]), 1.0).is_none(),
            "column past the entries"
        );
        assert!(
            clp::barrier(&program(vec![0], vec![0]), 1.0).is_none(),
            "starts too short"
        );
        let empty = LinearProgram {
            starts: vec![0],
            rows: vec![],
            values: vec![],
            objective: vec![],
            column_upper: vec![],
            row_upper: vec![],
        };
        assert!(clp::barrier(&empty, 1.0).is_some_and(|d| d.converged && d.row_duals.is_empty()));
    }
}
