//! The paper's binary integer programs (eqs. 1-3) solved with CBC through `good_lp`, on the
//! whole dual graph or on a window of it with the rest of the pattern held fixed.

use std::collections::HashMap;
use std::time::Duration;

use good_lp::solvers::coin_cbc::coin_cbc;
use good_lp::{
    Expression, ProblemVariables, ResolutionError, Solution, SolutionStatus, SolverModel, Variable,
    constraint, variable,
};

use super::{Bond, DualGraph, Formulation, PatternError, score, worker};
use crate::control::Control;

/// CBC gets this share of the time limit, so that it can stop and hand over its incumbent
/// before the caller's deadline.
const CBC_SHARE_OF_LIMIT: f64 = 0.9;

/// Which tiles a solve may change.
pub(super) struct Restriction<'a> {
    /// Tiles the solver may choose or not.
    pub free: &'a [bool],
    /// Tiles chosen and held fixed; they block their faces and enter the bond terms as
    /// constants.
    pub fixed: &'a [bool],
    /// Solve the relaxation of one patch of a decomposition instead (see [`Patch`]).
    pub patch: Option<Patch<'a>>,
}

/// The relaxed program of one patch of a partition of the faces, whose optima add up to an
/// upper bound on the whole program's optimum (see `decompose`): only the patch's faces are
/// constrained, each scores half a tile when covered (so a tile reaching out of the patch
/// scores 1/2 and its outer face is free), and only the bond pairs the patch owns are
/// counted. A penalty pair with a tile outside the patch is left out (which can only raise
/// the bound); a reward pair with its second tile outside is bounded by the first tile alone.
#[derive(Clone, Copy)]
pub(super) struct Patch<'a> {
    /// The patch's faces.
    pub faces: &'a [bool],
    /// `owned[i]`: the patch owns pair `i` of the bond's relation (continuous joints or
    /// shifted pairs); every pair is owned by exactly one patch.
    pub owned: &'a [bool],
}

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

/// About how long CBC's root linear program takes on a program over `faces` faces. Clp's
/// simplex method does not check the clock, and a solve that outlives its deadline keeps
/// CBC's process-wide lock until it ends, so the engine starts none it does not expect to
/// finish in time.
pub(super) fn expected_linear_seconds(faces: usize) -> f64 {
    LINEAR_SECONDS_AT_1000_FACES * (faces as f64 / 1000.0).powf(LINEAR_TIME_EXPONENT)
}

/// Solves the bond's program over the free tiles of `restriction`.
pub(super) fn solve(
    graph: &DualGraph,
    bond: Bond,
    formulation: Formulation,
    restriction: &Restriction<'_>,
    time_limit: Duration,
    control: &mut Control<'_>,
    progress: impl Fn() -> f64,
) -> Result<Outcome, PatternError> {
    let tiles = graph.tiles();
    let mut blocked = vec![false; graph.face_count()];
    for (t, _) in restriction.fixed.iter().enumerate().filter(|(_, on)| **on) {
        tiles[t].faces.iter().for_each(|&f| blocked[f] = true);
    }
    let patch = restriction.patch;
    let counted = |f: usize| patch.is_none_or(|p| p.faces[f]);
    let owned = |i: usize| patch.is_none_or(|p| p.owned[i]);
    let usable: Vec<bool> = (0..tiles.len())
        .map(|t| {
            restriction.free[t]
                && !tiles[t].faces.iter().any(|&f| blocked[f])
                && tiles[t].faces.iter().any(|&f| counted(f))
        })
        .collect();
    let constant = score(graph, restriction.fixed, bond).objective;

    let mut vars = ProblemVariables::new();
    let x: Vec<Option<Variable>> = usable
        .iter()
        .map(|&u| u.then(|| vars.add(variable().binary())))
        .collect();
    // A tile scores one, or in a patch half per face of the patch it covers.
    let mut objective: Expression = x
        .iter()
        .enumerate()
        .filter_map(|(t, v)| {
            v.map(|v| 0.5 * tiles[t].faces.iter().filter(|&&f| counted(f)).count() as f64 * v)
        })
        .sum();
    let mut rows = Vec::new();

    // Eq. (1): each face in at most one tile.
    for f in (0..graph.face_count()).filter(|&f| counted(f)) {
        let around: Vec<Variable> = graph.face_tiles(f).iter().filter_map(|&t| x[t]).collect();
        if around.len() > 1 {
            rows.push(constraint!(around.into_iter().sum::<Expression>() <= 1));
        }
    }
    // A bond pair between a free and a fixed tile is linear in the free tile's x.
    let linear_partner = |[a, b]: [usize; 2]| match (x[a], x[b]) {
        (Some(v), None) if restriction.fixed[b] => Some(v),
        (None, Some(v)) if restriction.fixed[a] => Some(v),
        _ => None,
    };
    match bond {
        Bond::Stack => {}
        Bond::Staggered { weight } => {
            // Eq. (2): y >= x1 + x2 - 1 and a penalty w per continuous joint.
            let mut y_of = HashMap::new();
            for pair in graph
                .continuous_joints()
                .iter()
                .enumerate()
                .filter(|&(i, _)| owned(i))
                .map(|(_, &pair)| pair)
            {
                if let (Some(a), Some(b)) = (x[pair[0]], x[pair[1]]) {
                    let y = vars.add(variable().binary());
                    objective -= weight * y;
                    rows.push(constraint!(a + b - y <= 1));
                    y_of.insert(pair, y);
                } else if let Some(v) = linear_partner(pair) {
                    objective -= weight * v;
                }
            }
            if formulation == Formulation::Strengthened {
                let y = |a: usize, b: usize| y_of.get(&[a.min(b), a.max(b)]).copied();
                // Valid where the four faces around the vertex are constrained.
                let inside = |t: usize| tiles[t].faces.iter().all(|&f| counted(f));
                for &[a, b, c, d] in graph
                    .regular_vertex_stars()
                    .iter()
                    .filter(|star| star.iter().all(|&t| inside(t)))
                {
                    if let (Some(xa), Some(xb), Some(xc), Some(xd), Some(yac), Some(ybd)) =
                        (x[a], x[b], x[c], x[d], y(a, c), y(b, d))
                    {
                        rows.push(constraint!(xa + xb + xc + xd - yac - ybd <= 1));
                    }
                }
            }
        }
        Bond::RunningBond { weight } => {
            // Eq. (3): z <= x1, z <= x2 and a reward w_R per shifted pair.
            for pair in graph
                .shifted_pairs()
                .iter()
                .enumerate()
                .filter(|&(i, _)| owned(i))
                .map(|(_, &pair)| pair)
            {
                if let (Some(a), Some(b)) = (x[pair[0]], x[pair[1]]) {
                    let z = vars.add(variable().binary());
                    objective += weight * z;
                    rows.push(constraint!(z <= a));
                    rows.push(constraint!(z <= b));
                } else if let Some(v) = linear_partner(pair) {
                    objective += weight * v;
                } else if let (Some(v), true) = (x[pair[0]].or(x[pair[1]]), patch.is_some()) {
                    // The partner lies outside the patch: it might be chosen.
                    objective += weight * v;
                }
            }
        }
    }
    let columns: Vec<(usize, Variable)> = x
        .iter()
        .enumerate()
        .filter_map(|(t, v)| v.map(|v| (t, v)))
        .collect();
    if columns.is_empty() {
        return Ok(Outcome {
            chosen: Some(vec![false; tiles.len()]),
            bound: constant,
            timed_out: false,
        });
    }

    let mut problem = vars.maximise(objective).using(coin_cbc);
    problem.set_parameter("log", "0");
    problem.set_parameter("slog", "0");
    problem.set_parameter("timeMode", "elapsed");
    problem.set_parameter(
        "sec",
        &format!(
            "{:.3}",
            (time_limit.as_secs_f64() * CBC_SHARE_OF_LIMIT).max(0.001)
        ),
    );
    for row in rows {
        problem.add_constraint(row);
    }

    // CBC checks its clock in branch-and-bound but not while Clp solves the root LP, which
    // can take minutes on a large staggered model. It therefore runs on a worker thread and
    // the caller gets what is known at the deadline; a worker that outlives it stops at CBC's
    // own limit right after its LP and is discarded. The engine keeps windows small so this
    // only happens when a caller asks for the whole model on a large mesh.
    let worker = move || {
        problem.solve().map(|solution| {
            let values: Vec<(usize, f64)> = columns
                .iter()
                .map(|&(t, v)| (t, solution.value(v)))
                .collect();
            let timed_out = matches!(solution.status(), SolutionStatus::TimeLimit);
            (values, solution.model().best_possible_value(), timed_out)
        })
    };
    let Some(result) = worker::run(worker, time_limit, control, progress)? else {
        return Ok(Outcome {
            chosen: None,
            bound: f64::INFINITY,
            timed_out: true,
        });
    };
    // CBC stopped by its time limit before it had a solution may call the problem
    // infeasible; every program here is feasible (no tiles at all).
    if matches!(result, Err(ResolutionError::Infeasible)) {
        return Ok(Outcome {
            chosen: None,
            bound: f64::INFINITY,
            timed_out: true,
        });
    }
    let (values, bound, timed_out) = result.map_err(|e| match e {
        ResolutionError::Other(message) => PatternError::Solver(message.to_string()),
        other => PatternError::Solver(other.to_string()),
    })?;
    let bound = if bound.is_finite() {
        bound + constant
    } else {
        f64::INFINITY
    };
    let mut chosen = vec![false; tiles.len()];
    for (t, value) in values {
        chosen[t] = value > 0.5;
    }
    Ok(Outcome {
        chosen: Some(chosen),
        bound,
        timed_out,
    })
}
