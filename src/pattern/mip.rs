//! The paper's binary integer programs (eqs. 1-3) solved with CBC through `good_lp`.

use std::collections::HashMap;
use std::time::Duration;

use good_lp::solvers::coin_cbc::coin_cbc;
use good_lp::{
    Expression, ProblemVariables, ResolutionError, Solution, SolutionStatus, SolverModel, Variable, WithInitialSolution,
    constraint, variable,
};

use super::{Bond, DualGraph, Formulation, PatternError};

/// What the solver returned, before it is turned into a [`super::Pattern`].
pub(super) struct Outcome {
    /// Chosen candidate tiles (a valid matching containing every forced tile).
    pub chosen: Vec<bool>,
    /// Proven upper bound on the objective.
    pub bound: f64,
    /// CBC finished its search.
    pub proven: bool,
    /// CBC stopped on the time limit.
    pub timed_out: bool,
}

/// Solves the bond's program on `graph`, every tile in `forced` fixed to 1.
pub(super) fn solve(
    graph: &DualGraph,
    bond: Bond,
    formulation: Formulation,
    forced: &[usize],
    time_limit: Duration,
) -> Result<Outcome, PatternError> {
    let start = greedy_matching(graph, forced);
    if graph.tiles().is_empty() || time_limit.is_zero() {
        return Ok(Outcome { bound: trivial_bound(graph, bond), proven: graph.tiles().is_empty(), timed_out: true, chosen: start });
    }

    let mut vars = ProblemVariables::new();
    let x: Vec<Variable> = graph.tiles().iter().map(|_| vars.add(variable().binary())).collect();
    let mut objective: Expression = x.iter().sum();
    let mut rows = Vec::new();
    let mut initial: Vec<(Variable, f64)> = x.iter().zip(&start).map(|(&v, &on)| (v, f64::from(u8::from(on)))).collect();
    let both_on = |[a, b]: [usize; 2]| f64::from(u8::from(start[a] && start[b]));

    // Eq. (1): each face in at most one tile.
    for f in 0..graph.face_count() {
        let around = graph.face_tiles(f);
        if !around.is_empty() {
            rows.push(constraint!(around.iter().map(|&t| x[t]).sum::<Expression>() <= 1));
        }
    }
    match bond {
        Bond::Stack => {}
        Bond::Staggered { weight } => {
            // Eq. (2): y >= x1 + x2 - 1 and a penalty w per continuous joint.
            let mut y_of = HashMap::new();
            for &pair in graph.continuous_joints() {
                let y = vars.add(variable().binary());
                objective -= weight * y;
                rows.push(constraint!(x[pair[0]] + x[pair[1]] - y <= 1));
                initial.push((y, both_on(pair)));
                y_of.insert(pair, y);
            }
            if formulation == Formulation::Strengthened {
                let key = |a: usize, b: usize| y_of[&[a.min(b), a.max(b)]];
                for &[a, b, c, d] in graph.regular_vertex_stars() {
                    rows.push(constraint!(x[a] + x[b] + x[c] + x[d] - key(a, c) - key(b, d) <= 1));
                }
            }
        }
        Bond::RunningBond { weight } => {
            // Eq. (3): z <= x1, z <= x2 and a reward w_R per shifted pair.
            for &pair in graph.shifted_pairs() {
                let z = vars.add(variable().binary());
                objective += weight * z;
                rows.push(constraint!(z <= x[pair[0]]));
                rows.push(constraint!(z <= x[pair[1]]));
                initial.push((z, both_on(pair)));
            }
        }
    }
    for &t in forced {
        rows.push(constraint!(x[t] == 1));
    }

    let mut problem = vars.maximise(objective).using(coin_cbc);
    problem.set_parameter("log", "0");
    problem.set_parameter("slog", "0");
    problem.set_parameter("threads", "1");
    problem.set_parameter("timeMode", "elapsed");
    problem.set_parameter("sec", &format!("{:.3}", time_limit.as_secs_f64()));
    for row in rows {
        problem.add_constraint(row);
    }
    let solution = problem.with_initial_solution(initial).solve().map_err(|e| match e {
        ResolutionError::Other(message) => PatternError::Solver(message.to_string()),
        other => PatternError::Solver(other.to_string()),
    })?;

    let chosen: Vec<bool> = x.iter().map(|&v| solution.value(v) > 0.5).collect();
    let status = solution.status();
    let bound = solution.model().best_possible_value();
    // On a time limit without an incumbent CBC still hands back values: keep them only if
    // they form a matching that honours the forced tiles.
    let chosen = if is_matching(graph, &chosen) && forced.iter().all(|&t| chosen[t]) { chosen } else { start };
    let bound = if bound.is_finite() { bound } else { trivial_bound(graph, bond) };
    Ok(Outcome {
        chosen,
        bound: bound.min(trivial_bound(graph, bond)),
        proven: matches!(status, SolutionStatus::Optimal),
        timed_out: matches!(status, SolutionStatus::TimeLimit),
    })
}

/// A maximal matching that starts from the forced tiles and adds tiles in index order.
fn greedy_matching(graph: &DualGraph, forced: &[usize]) -> Vec<bool> {
    let mut chosen = vec![false; graph.tiles().len()];
    let mut used = vec![false; graph.face_count()];
    for t in forced.iter().copied().chain(0..graph.tiles().len()) {
        let [a, b] = graph.tiles()[t].faces;
        if !used[a] && !used[b] {
            used[a] = true;
            used[b] = true;
            chosen[t] = true;
        }
    }
    chosen
}

/// True when no face is in two chosen tiles.
fn is_matching(graph: &DualGraph, chosen: &[bool]) -> bool {
    let mut used = vec![false; graph.face_count()];
    graph
        .tiles()
        .iter()
        .zip(chosen)
        .filter(|(_, c)| **c)
        .all(|(tile, _)| tile.faces.iter().all(|&f| !std::mem::replace(&mut used[f], true)))
}

/// A bound that needs no solver: half the faces that have a candidate tile (plus every
/// shifted pair's reward for the running bond).
fn trivial_bound(graph: &DualGraph, bond: Bond) -> f64 {
    let pairable = (0..graph.face_count()).filter(|&f| !graph.face_tiles(f).is_empty()).count();
    let tiles = (pairable / 2) as f64;
    match bond {
        Bond::RunningBond { weight } => tiles + weight * graph.shifted_pairs().len() as f64,
        Bond::Stack | Bond::Staggered { .. } => tiles,
    }
}
