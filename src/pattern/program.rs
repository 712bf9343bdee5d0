//! The paper's program (section 3.4, eqs. 1-3), written once: built from the dual graph,
//! the bond, the tiles a caller holds fixed or leaves out, and optionally one patch of a
//! decomposition, as a solver-neutral [`Model`]. CBC solves it as an integer program
//! (`mip`), Clp's barrier its linear relaxation (`linear`); both read it from here, and
//! `Program::objective_at` (test builds) evaluates it, so that a test holds it to
//! [`score`](super::score()).
//!
//! * A column `x_t` per candidate tile the program may choose, worth one tile, or in a
//!   patch half a tile per face of the patch it covers.
//! * Eq. (1): per face, the sum of its tiles' `x` at most 1.
//! * Eq. (2), staggered, a penalty `w` per continuous joint: `y >= x_a + x_b - 1`. In the
//!   compact joint form ([`Formulation::Strengthened`]) a regular vertex whose four tiles
//!   `a, b, c, d` are all columns inside the patch has one column `s` for its two joints and
//!   one star row `x_a + x_b + x_c + x_d - s <= 1`: with the face rows (the four `x` sum to at
//!   most 2) the set `{y_ac, y_bd in [0, 1] : y_ac >= x_a + x_c - 1, y_bd >= x_b + x_d - 1,
//!   y_ac + y_bd >= x_a + x_b + x_c + x_d - 1}` projects onto `s = y_ac + y_bd` as exactly
//!   `s >= x_a + x_b + x_c + x_d - 1, s >= 0`, so the optimum and the relaxation are those
//!   of the paper's program with the star rows, with two columns and two rows fewer per
//!   vertex. For integer `x`, `s` is the number of joints at the vertex. Every joint belongs
//!   to one vertex (the dual graph records which), so no joint is counted twice.
//! * Eq. (3), running bond, a reward `w_R` per shifted pair: `z <= x_a`, `z <= x_b`.
//! * In the strengthened form, a course closed on itself over an odd number `k` of faces
//!   (a ring of a tower, a drum or a dome in level courses: a component of the dual graph
//!   where every face has two tiles) holds at most `(k - 1) / 2` tiles, one row over its
//!   `k` tiles: Edmonds' odd-set (blossom) inequality of the matching polytope, which eq.
//!   (1) alone leaves at `k / 2` (every tile at one half). Without it CBC, which searches a
//!   program in courses without cuts, branches on every odd ring: a tower of 20 rings of 95
//!   quads took 32 s to prove.
//!
//! One rule for the tiles around a restriction, whatever the solver:
//! * a *fixed* tile is chosen: it blocks its faces (their other tiles get no column), adds
//!   its worth to the constant, and a bond pair with it is linear in its partner's `x` (or
//!   a constant when both are fixed);
//! * a tile neither free nor fixed, or blocked, is not chosen: its pairs count nothing;
//! * in a patch, a tile with no face in the patch is *outside*: it might be chosen or not.
//!   A penalty pair with it is left out (which can only raise the patch's bound), a reward
//!   pair is bounded by its other tile alone. Only the pairs the patch owns count.

use super::{DualGraph, Formulation, Terms};
use crate::solver::{Model, Row};

/// Which tiles a program may change.
pub(super) struct Restriction<'a> {
    /// Tiles the program may choose or not.
    pub free: &'a [bool],
    /// Tiles chosen and held fixed; they block their faces and enter the bond terms as
    /// constants.
    pub fixed: &'a [bool],
    /// The relaxed program of one patch instead of the whole one (see [`Patch`]).
    pub patch: Option<Patch<'a>>,
}

/// The relaxed program of one patch of a partition of the faces, whose optima add up to an
/// upper bound on the whole program's optimum (see `decompose`): only the patch's faces are
/// constrained, each scores half a tile when covered (so a tile reaching out of the patch
/// scores 1/2 and its outer face is free), and only the bond pairs the patch owns are
/// counted, by the rule for tiles outside the patch (see the module documentation).
#[derive(Clone, Copy)]
pub(super) struct Patch<'a> {
    /// The patch's faces.
    pub faces: &'a [bool],
    /// `owned[i]`: the patch owns pair `i` of the bond's relation (continuous joints or
    /// shifted pairs); every pair is owned by exactly one patch.
    pub owned: &'a [bool],
}

/// What a candidate tile is to one program.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Role {
    /// The program chooses it: its column.
    Column(usize),
    /// Chosen and held.
    Fixed,
    /// Not chosen (not free, or blocked by a fixed tile).
    Off,
    /// No face in the patch: unknown to the patch's program.
    Outside,
}

/// The program of eqs. (1)-(3) for one bond, restriction and formulation.
pub(super) struct Program {
    model: Model,
    role: Vec<Role>,
    /// Objective of what is held fixed.
    constant: f64,
}

impl Program {
    /// Builds the program (see the module documentation for its rules).
    pub fn new(
        graph: &DualGraph,
        terms: &Terms<'_>,
        formulation: Formulation,
        restriction: &Restriction<'_>,
    ) -> Self {
        let tiles = graph.tiles();
        let patch = restriction.patch;
        let counted = |f: usize| patch.is_none_or(|p| p.faces[f]);
        let owned = |i: usize| patch.is_none_or(|p| p.owned[i]);
        // One tile, or in a patch half a tile per face of the patch it covers.
        let worth = |t: usize| 0.5 * tiles[t].faces.iter().filter(|&&f| counted(f)).count() as f64;
        let mut blocked = vec![false; graph.face_count()];
        for (t, _) in restriction.fixed.iter().enumerate().filter(|(_, on)| **on) {
            tiles[t].faces.iter().for_each(|&f| blocked[f] = true);
        }
        let mut objective = Vec::new();
        let mut constant = 0.0;
        let role: Vec<Role> = (0..tiles.len())
            .map(|t| {
                let worth = worth(t);
                if restriction.fixed[t] {
                    constant += worth;
                    Role::Fixed
                } else if worth == 0.0 {
                    Role::Outside
                } else if restriction.free[t] && !tiles[t].faces.iter().any(|&f| blocked[f]) {
                    objective.push(worth);
                    Role::Column(objective.len() - 1)
                } else {
                    Role::Off
                }
            })
            .collect();
        let column = |t: usize| match role[t] {
            Role::Column(j) => Some(j),
            _ => None,
        };
        let mut rows: Vec<Row> = Vec::new();
        // Eq. (1): each face in at most one tile.
        for f in (0..graph.face_count()).filter(|&f| counted(f)) {
            let around: Vec<(usize, f64)> = graph
                .face_tiles(f)
                .iter()
                .filter_map(|&t| column(t))
                .map(|j| (j, 1.0))
                .collect();
            if around.len() > 1 {
                rows.push((around, 1.0));
            }
        }
        // Eq. (2) in the compact joint form: one column and one star row per regular vertex
        // whose four tiles are columns with all their faces in the patch, its two joints
        // scored at one penalty and owned.
        let mut starred = vec![false; terms.pairs().len()];
        let inside = |t: usize| tiles[t].faces.iter().all(|&f| counted(f));
        if formulation == Formulation::Strengthened {
            for (star, joints) in graph
                .regular_vertex_stars()
                .iter()
                .zip(graph.regular_vertex_star_joints())
            {
                let [Some(ac), Some(bd)] = joints.map(|j| terms.joint_term(j)) else {
                    continue;
                };
                let penalty = terms.weight(ac);
                let columns: Vec<usize> = star.iter().filter_map(|&t| column(t)).collect();
                if penalty < 0.0
                    && terms.weight(bd) == penalty
                    && columns.len() == 4
                    && star.iter().all(|&t| inside(t))
                    && owned(ac)
                    && owned(bd)
                {
                    starred[ac] = true;
                    starred[bd] = true;
                    objective.push(penalty);
                    let mut row: Vec<(usize, f64)> = columns.iter().map(|&j| (j, 1.0)).collect();
                    row.push((objective.len() - 1, -1.0));
                    rows.push((row, 1.0));
                }
            }
        }
        // Odd closed courses of the whole program: at most (k - 1) / 2 of their k tiles.
        if formulation == Formulation::Strengthened && patch.is_none() {
            for ring in odd_rings(graph, &|t| column(t).is_some()) {
                let row = ring
                    .iter()
                    .filter_map(|&t| column(t))
                    .map(|j| (j, 1.0))
                    .collect();
                rows.push((row, ((ring.len() - 1) / 2) as f64));
            }
        }
        // Every other pair the program owns, by the roles of its two tiles.
        for (_, [a, b], per_pair) in terms.iter().filter(|&(i, _, _)| owned(i) && !starred[i]) {
            match (role[a], role[b]) {
                (Role::Column(xa), Role::Column(xb)) => {
                    objective.push(per_pair);
                    let pair = objective.len() - 1;
                    if per_pair < 0.0 {
                        // Eq. (2) and every penalty pair: y >= x_a + x_b - 1; strengthened
                        // by the tiles bridging the two (see `bridges`).
                        let mut row = vec![(xa, 1.0), (xb, 1.0), (pair, -1.0)];
                        if formulation == Formulation::Strengthened {
                            row.extend(
                                bridges(graph, a, b, &inside)
                                    .into_iter()
                                    .filter_map(&column)
                                    .map(|j| (j, 1.0)),
                            );
                        }
                        rows.push((row, 1.0));
                    } else if per_pair > 0.0 {
                        // Eq. (3): z <= x_a and z <= x_b.
                        rows.push((vec![(xa, -1.0), (pair, 1.0)], 0.0));
                        rows.push((vec![(xb, -1.0), (pair, 1.0)], 0.0));
                    }
                }
                (Role::Column(x), Role::Fixed) | (Role::Fixed, Role::Column(x)) => {
                    objective[x] += per_pair;
                }
                (Role::Fixed, Role::Fixed) => constant += per_pair,
                // A partner outside the patch: a reward is bounded by the tile inside alone,
                // a penalty left out.
                (Role::Column(x), Role::Outside) | (Role::Outside, Role::Column(x))
                    if per_pair > 0.0 =>
                {
                    objective[x] += per_pair;
                }
                (Role::Fixed, Role::Outside) | (Role::Outside, Role::Fixed) if per_pair > 0.0 => {
                    constant += per_pair;
                }
                _ => {}
            }
        }
        let columns = objective.len();
        Self {
            model: Model::from_rows(&rows, objective, vec![1.0; columns], vec![true; columns]),
            role,
            constant,
        }
    }

    /// The model, for a solver: its objective plus [`Program::constant`] is the bond's.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Objective of what the restriction holds fixed.
    pub fn constant(&self) -> f64 {
        self.constant
    }

    /// The tiles a solution of the model (a value per column) chooses, indexed like
    /// [`DualGraph::tiles`]; fixed tiles are not included.
    pub fn chosen(&self, values: &[f64]) -> Vec<bool> {
        self.role
            .iter()
            .map(|r| matches!(r, Role::Column(j) if values.get(*j).is_some_and(|&v| v > 0.5)))
            .collect()
    }

    /// The program's objective at the pattern `chosen` (indexed like [`DualGraph::tiles`],
    /// fixed tiles included), its joint and pair columns at their best values for it; `None`
    /// when `chosen` is not a solution (it drops a fixed tile, takes a tile the program
    /// leaves out, or breaks a row).
    #[cfg(test)]
    pub fn objective_at(&self, chosen: &[bool]) -> Option<f64> {
        let model = &self.model;
        let mut values = vec![0.0; model.columns()];
        let mut tile_columns = vec![false; model.columns()];
        for (t, role) in self.role.iter().enumerate() {
            match (*role, chosen[t]) {
                (Role::Column(j), on) => {
                    tile_columns[j] = true;
                    values[j] = if on { 1.0 } else { 0.0 };
                }
                (Role::Fixed, false) | (Role::Off, true) => return None,
                _ => {}
            }
        }
        let mut activity = vec![0.0; model.row_upper.len()];
        for j in (0..model.columns()).filter(|&j| tile_columns[j]) {
            model
                .column(j)
                .for_each(|(r, a)| activity[r] += a * values[j]);
        }
        // Each joint or pair column is in rows of its own, with tile columns only: the
        // least value they allow for a penalty, the largest for a reward.
        for j in (0..model.columns()).filter(|&j| !tile_columns[j]) {
            let (mut lower, mut upper) = (0.0_f64, model.column_upper[j]);
            for (r, a) in model.column(j) {
                let slack = model.row_upper[r] - activity[r];
                if a > 0.0 {
                    upper = upper.min(slack / a);
                } else {
                    lower = lower.max(slack / a);
                }
            }
            if lower > upper + 1e-9 {
                return None;
            }
            values[j] = if model.objective[j] > 0.0 {
                upper
            } else {
                lower
            };
            model
                .column(j)
                .for_each(|(r, a)| activity[r] += a * values[j]);
        }
        if activity
            .iter()
            .zip(&model.row_upper)
            .any(|(a, b)| *a > b + 1e-9)
        {
            return None;
        }
        Some(
            self.constant
                + values
                    .iter()
                    .zip(&model.objective)
                    .map(|(v, c)| v * c)
                    .sum::<f64>(),
        )
    }
}

/// The tiles of every odd ring of the dual graph restricted to the tiles `usable`: a
/// connected component (faces joined by usable tiles) where every face has exactly two usable
/// tiles, so that its faces and tiles form one cycle, of an odd number of faces. Each ring's
/// tiles in index order, the rings by their smallest face.
fn odd_rings(graph: &DualGraph, usable: &impl Fn(usize) -> bool) -> Vec<Vec<usize>> {
    let tiles = graph.tiles();
    let around = |f: usize| graph.face_tiles(f).iter().copied().filter(|&t| usable(t));
    let mut seen = vec![false; graph.face_count()];
    let mut rings = Vec::new();
    for start in 0..graph.face_count() {
        if seen[start] || around(start).count() != 2 {
            continue;
        }
        seen[start] = true;
        let (mut faces, mut ring, mut cycle) = (0, Vec::new(), true);
        let mut stack = vec![start];
        while let Some(f) = stack.pop() {
            faces += 1;
            cycle &= around(f).count() == 2;
            for t in around(f) {
                let [a, b] = tiles[t].faces;
                let other = if a == f { b } else { a };
                if !seen[other] {
                    seen[other] = true;
                    stack.push(other);
                }
                if f == a {
                    ring.push(t);
                }
            }
        }
        if cycle && faces % 2 == 1 && ring.len() == faces {
            ring.sort_unstable();
            rings.push(ring);
        }
    }
    rings
}

/// The tiles that share a face with each of the penalty pair `a`, `b` (both with all their
/// faces `inside` the program), kept only while they pairwise share a face, so that of
/// `a`, `b` and the bridges at most one is chosen unless `a` and `b` both are: then
/// `x_a + x_b + sum of the bridges' x - y <= 1` holds for every pattern and cuts off
/// fractional points that `y >= x_a + x_b - 1` allows (the end-to-end and shifted pairs'
/// counterpart of the star rows). Empty when a tile is not inside.
fn bridges(graph: &DualGraph, a: usize, b: usize, inside: &impl Fn(usize) -> bool) -> Vec<usize> {
    let tiles = graph.tiles();
    let share = |s: usize, t: usize| tiles[s].faces.iter().any(|f| tiles[t].faces.contains(f));
    if !(inside(a) && inside(b)) {
        return Vec::new();
    }
    let mut found: Vec<usize> = Vec::new();
    for &t in tiles[a].faces.iter().flat_map(|&f| graph.face_tiles(f)) {
        let fits = t != a && t != b && share(t, b) && inside(t);
        if fits && !found.contains(&t) && found.iter().all(|&u| share(u, t)) {
            found.push(t);
        }
    }
    found
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::mesh::{PolyMesh, Topology, generate};
    use crate::pattern::decompose::tests::ragged;
    use crate::pattern::score::evaluate;
    use crate::pattern::{Bond, courses};

    /// xorshift: deterministic pseudo-random numbers for the property tests.
    struct Rng(u64);

    impl Rng {
        fn below(&mut self, n: usize) -> usize {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 % n as u64) as usize
        }
    }

    /// `k` quads around one vertex (valence `k`), ringed by `2k` more: singular at the
    /// centre, and valence 3 at every other vertex of the first ring.
    fn star(k: usize) -> PolyMesh {
        use nalgebra::Point3;
        let at = |r: f64, i: usize| {
            let a = std::f64::consts::TAU * i as f64 / (2 * k) as f64;
            Point3::new(r * a.cos(), r * a.sin(), 0.0)
        };
        let first = |i: usize| 1 + i % (2 * k);
        let second = |i: usize| 1 + 2 * k + i % (2 * k);
        let mut points = vec![Point3::origin()];
        points.extend((0..2 * k).map(|i| at(1.0, i)));
        points.extend((0..2 * k).map(|i| at(2.0, i)));
        let mut faces: Vec<Vec<usize>> = (0..k)
            .map(|i| vec![0, first(2 * i), first(2 * i + 1), first(2 * i + 2)])
            .collect();
        faces.extend((0..2 * k).map(|i| vec![first(i), second(i), second(i + 1), first(i + 1)]));
        PolyMesh::new(points, faces).unwrap()
    }

    /// A tube of quads: `around` faces round its axis (z), `rows` rings of them; in level
    /// courses each ring is a course closed on itself.
    pub(crate) fn tube(around: usize, rows: usize) -> PolyMesh {
        use nalgebra::Point3;
        let at = |i: usize, j: usize| j * around + i % around;
        let points = (0..=rows)
            .flat_map(|j| {
                (0..around).map(move |i| {
                    let a = std::f64::consts::TAU * i as f64 / around as f64;
                    Point3::new(a.cos(), a.sin(), 0.8 * j as f64)
                })
            })
            .collect();
        let faces = (0..rows)
            .flat_map(|j| {
                (0..around)
                    .map(move |i| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
            })
            .collect();
        PolyMesh::new(points, faces).unwrap()
    }

    /// The dual graph of [`tube`] in level courses (up along its axis): each ring a course
    /// closed on itself.
    pub(crate) fn tube_in_courses(around: usize, rows: usize) -> DualGraph {
        let mesh = tube(around, rows);
        let topology = Topology::new(&mesh).unwrap();
        let middle = courses::middle_edges(&mesh, &topology, [0.0, 0.0, 1.0]).unwrap();
        DualGraph::restricted(&mesh, &topology, &[], Some(&middle))
    }

    /// A random pattern: the tiles in random order, each taken with probability 3/4 when
    /// its faces are still free.
    fn random_pattern(graph: &DualGraph, rng: &mut Rng) -> Vec<bool> {
        let tiles = graph.tiles();
        let mut order: Vec<usize> = (0..tiles.len()).collect();
        for i in (1..order.len()).rev() {
            order.swap(i, rng.below(i + 1));
        }
        let mut used = vec![false; graph.face_count()];
        let mut chosen = vec![false; tiles.len()];
        for t in order {
            if rng.below(4) > 0 && tiles[t].faces.iter().all(|&f| !used[f]) {
                tiles[t].faces.iter().for_each(|&f| used[f] = true);
                chosen[t] = true;
            }
        }
        chosen
    }

    /// Dual graphs of every kind: grids, ragged boundaries, singular vertices (valence 3 and
    /// 5), excluded faces, tiles restricted to courses, courses closed on themselves (odd
    /// and even rings of a tube).
    fn graphs() -> Vec<DualGraph> {
        let mut graphs = vec![tube_in_courses(7, 3), tube_in_courses(6, 2)];
        for mesh in [
            generate::grid(6, 5),
            ragged(8),
            star(3),
            star(5),
            generate::corner_supported_shell(3.0, 0.4),
        ] {
            let topology = Topology::new(&mesh).unwrap();
            graphs.push(DualGraph::new(&mesh, &topology, &[]));
            let excluded: Vec<bool> = (0..mesh.face_count()).map(|f| f % 7 == 3).collect();
            graphs.push(DualGraph::new(&mesh, &topology, &excluded));
            let middle = courses::middle_edges(&mesh, &topology, [0.0, 1.0, 0.3]).unwrap();
            graphs.push(DualGraph::restricted(&mesh, &topology, &[], Some(&middle)));
        }
        graphs
    }

    const BONDS: [Bond; 9] = [
        Bond::Stack,
        Bond::Staggered { weight: 0.5 },
        Bond::Staggered { weight: 2.0 },
        Bond::RunningBond { weight: 0.5 },
        Bond::RunningBond { weight: 1.5 },
        Bond::Herringbone { weight: 0.5 },
        Bond::Herringbone { weight: 0.2 },
        Bond::BasketWeave { weight: 0.5 },
        Bond::BasketWeave { weight: 0.2 },
    ];

    /// The terms of every bond on every face, and of zones: bands of faces (by index) in
    /// two or three bonds, and a bond drawn per face.
    fn objectives<'g>(graph: &'g DualGraph, rng: &mut Rng) -> Vec<(String, Terms<'g>)> {
        let faces = graph.face_count();
        let mut objectives: Vec<(String, Terms<'g>)> = BONDS
            .iter()
            .map(|&bond| (format!("{bond:?}"), Terms::uniform(graph, bond)))
            .collect();
        for (a, b, c) in [(1, 5, 1), (3, 7, 0), (2, 3, 8), (6, 4, 2)] {
            let zones: Vec<Bond> = (0..faces)
                .map(|f| [BONDS[a], BONDS[b], BONDS[c]][f * 3 / faces])
                .collect();
            objectives.push((format!("bands {a} {b} {c}"), Terms::zoned(graph, &zones)));
        }
        let zones: Vec<Bond> = (0..faces).map(|_| BONDS[rng.below(BONDS.len())]).collect();
        objectives.push(("drawn per face".into(), Terms::zoned(graph, &zones)));
        objectives
    }

    #[test]
    fn the_program_scores_every_pattern_as_score_does() {
        let mut rng = Rng(0x2545_f491_4f6c_dd1d);
        for graph in graphs() {
            let n = graph.tiles().len();
            for _ in 0..20 {
                let chosen = random_pattern(&graph, &mut rng);
                // Some of its tiles held fixed, the rest free, with some tiles it leaves out.
                let fixed: Vec<bool> = chosen.iter().map(|&c| c && rng.below(3) == 0).collect();
                let free: Vec<bool> = (0..n)
                    .map(|t| !fixed[t] && (chosen[t] || rng.below(2) == 0))
                    .collect();
                let everything = vec![true; n];
                let nothing = vec![false; n];
                for (name, terms) in objectives(&graph, &mut rng) {
                    let want = evaluate(&graph, &chosen, &terms).objective;
                    for formulation in [Formulation::Paper, Formulation::Strengthened] {
                        for (free, fixed) in [(&everything, &nothing), (&free, &fixed)] {
                            let restriction = Restriction {
                                free,
                                fixed,
                                patch: None,
                            };
                            let program = Program::new(&graph, &terms, formulation, &restriction);
                            let got = program.objective_at(&chosen);
                            assert!(
                                got.is_some_and(|got| (got - want).abs() < 1e-9),
                                "{name} {formulation:?}: program {got:?}, score {want}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn patch_programs_add_up_to_at_least_the_score() {
        let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
        for graph in graphs() {
            let tiles = graph.tiles();
            let faces = graph.face_count();
            let n = tiles.len();
            for patches in [2, 3, 5] {
                // Bands of faces by index; each pair owned by the patch of its first tile's
                // first face.
                let patch_of: Vec<usize> = (0..faces).map(|f| f * patches / faces).collect();
                for _ in 0..10 {
                    let chosen = random_pattern(&graph, &mut rng);
                    let mut covered = vec![false; faces];
                    for (t, _) in chosen.iter().enumerate().filter(|(_, c)| **c) {
                        tiles[t].faces.iter().for_each(|&f| covered[f] = true);
                    }
                    for (name, terms) in objectives(&graph, &mut rng) {
                        let owner: Vec<usize> = terms
                            .pairs()
                            .iter()
                            .map(|&[a, _]| patch_of[tiles[a].faces[0]])
                            .collect();
                        let mut total = 0.0;
                        for p in 0..patches {
                            let in_patch: Vec<bool> = patch_of.iter().map(|&q| q == p).collect();
                            let owned: Vec<bool> = owner.iter().map(|&o| o == p).collect();
                            let restriction = Restriction {
                                free: &vec![true; n],
                                fixed: &vec![false; n],
                                patch: Some(Patch {
                                    faces: &in_patch,
                                    owned: &owned,
                                }),
                            };
                            let program = Program::new(
                                &graph,
                                &terms,
                                Formulation::Strengthened,
                                &restriction,
                            );
                            let got = program.objective_at(&chosen).unwrap();
                            // The rule, restated: half a tile per covered face of the patch;
                            // an owned pair with both tiles in the patch by the bond, with
                            // one outside as a reward bounded by the tile inside, a penalty
                            // left out.
                            let reaches = |t: usize| tiles[t].faces.iter().any(|&f| in_patch[f]);
                            let mut want = 0.5
                                * (0..faces).filter(|&f| in_patch[f] && covered[f]).count() as f64;
                            for (_, [a, b], per_pair) in terms.iter().filter(|&(i, _, _)| owned[i])
                            {
                                want += match (reaches(a), reaches(b)) {
                                    (true, true) if chosen[a] && chosen[b] => per_pair,
                                    (true, false) if per_pair > 0.0 && chosen[a] => per_pair,
                                    (false, true) if per_pair > 0.0 && chosen[b] => per_pair,
                                    _ => 0.0,
                                };
                            }
                            assert!(
                                (got - want).abs() < 1e-9,
                                "{name}, patch {p} of {patches}: program {got}, rule {want}"
                            );
                            total += got;
                        }
                        let whole = evaluate(&graph, &chosen, &terms).objective;
                        assert!(total >= whole - 1e-9, "{name}: {total} < {whole}");
                        if terms.is_empty() {
                            assert!((total - whole).abs() < 1e-9);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn an_odd_closed_course_gets_one_row_and_an_even_one_none() {
        // Two rings of `around` quads: both odd, or both even.
        for (around, rings) in [(7, 2), (6, 0), (5, 2)] {
            let graph = tube_in_courses(around, 2);
            assert!(graph.in_courses());
            let found = odd_rings(&graph, &|_| true);
            assert_eq!(found.len(), rings, "{around} round");
            for ring in &found {
                assert_eq!(ring.len(), around);
            }
            // Without one of its tiles a ring is a path: no row.
            let first = found.first().map(|r| r[0]);
            let broken = odd_rings(&graph, &|t| Some(t) != first);
            assert_eq!(broken.len(), found.len().saturating_sub(1));
        }
    }

    #[test]
    fn the_compact_form_has_one_column_and_one_row_per_regular_vertex() {
        // 6 x 5 grid: 20 interior vertices, each a full star; 30 faces.
        let mesh = generate::grid(6, 5);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let n = graph.tiles().len();
        let restriction = Restriction {
            free: &vec![true; n],
            fixed: &vec![false; n],
            patch: None,
        };
        let terms = Terms::uniform(&graph, Bond::Staggered { weight: 0.5 });
        let compact = Program::new(&graph, &terms, Formulation::Strengthened, &restriction);
        let paper = Program::new(&graph, &terms, Formulation::Paper, &restriction);
        let joints = graph.continuous_joints().len();
        assert_eq!(graph.regular_vertex_stars().len(), 20);
        assert_eq!(joints, 40);
        assert_eq!(paper.model().columns(), n + joints);
        assert_eq!(compact.model().columns(), n + 20);
        assert_eq!(
            paper.model().row_upper.len() - joints,
            compact.model().row_upper.len() - 20
        );
    }
}
