//! Singularity reduction on the integer lattice jumps (after QuadriFlow section 5, which
//! cancels position singularities with a minimum-cost flow; here a greedy shortest-path
//! variant of the same idea).
//!
//! Around every triangle whose cross field has no rotation, the lattice steps `m` should add
//! up to zero. A nonzero sum (its "curl", the Burgers vector of a lattice dislocation)
//! becomes a valence 3 / valence 5 pair of irregular quad vertices. Changing the step of one
//! edge moves the curl to the triangle across it; walking a curl along the shortest dual
//! path onto an opposite curl (or out through the boundary, when the boundary pinning
//! allows it) removes both defects, and the following least-squares solve spreads the
//! small stretch this costs over the surrounding quads.

use std::collections::{BTreeMap, VecDeque};

use nalgebra::Matrix2;

use super::surface::Surface;

/// Quarter turns counter-clockwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Rot(u8);

impl Rot {
    fn apply<T: Copy + std::ops::Neg<Output = T>>(self, v: [T; 2]) -> [T; 2] {
        match self.0 % 4 {
            0 => v,
            1 => [-v[1], v[0]],
            2 => [-v[0], -v[1]],
            _ => [v[1], -v[0]],
        }
    }
    fn inv(self) -> Rot {
        Rot((4 - self.0 % 4) % 4)
    }
    fn then(self, o: Rot) -> Rot {
        Rot((self.0 + o.0) % 4)
    }
}

/// Rounds a frame transfer matrix to the nearest quarter turn.
fn quarter_turns(t: &Matrix2<f64>) -> Rot {
    let angle = turn_angle(t);
    Rot(((angle / std::f64::consts::FRAC_PI_2).round() as i64).rem_euclid(4) as u8)
}

/// The angle (radians, in `(-pi, pi]`) of the rotation nearest to a frame transfer matrix.
pub(crate) fn turn_angle(t: &Matrix2<f64>) -> f64 {
    (t[(1, 0)] - t[(0, 1)]).atan2(t[(0, 0)] + t[(1, 1)])
}

/// The whole quarter turn nearest to a frame transfer matrix, as a rotation matrix: how the
/// integer lattice steps are carried between two frames.
pub(crate) fn quarter_turn_matrix(t: &Matrix2<f64>) -> Matrix2<f64> {
    let [c, s] = quarter_turns(t).apply([1.0, 0.0]);
    Matrix2::new(c, -s, s, c)
}

/// Lattice jumps with the connectivity to reason about their curls.
pub(crate) struct Jumps<'a> {
    s: &'a Surface,
    turns: Vec<Rot>,
    tri_edges: Vec<[usize; 3]>,
    edge_tris: Vec<[usize; 2]>,
}

const NONE: usize = usize::MAX;

/// Largest dislocation content (in Burgers vectors, whole lattice steps) a patch may ask for
/// and still have its lone dislocations walked out ([`Jumps::unwanted`]). Measured on the
/// guide test of `tests/guides.rs` (a guide at 30 degrees to the designer's field): its
/// patches ask for about 2-3.5 and their dislocations must stay; those the integration leaves
/// on an evenly triangulated vault sit in patches asking for 0.05-0.25. (Measured while the
/// density read each step in its start frame, which made it twice as long and turned it by
/// a quarter; [`super::scale`]'s `mid_step` reads it halfway. The tests still hold.)
const CALM: f64 = 0.5;

impl<'a> Jumps<'a> {
    /// Prepares curl bookkeeping for `s` with per-edge frame transfers `transfer`.
    pub fn new(s: &'a Surface, transfer: &[Matrix2<f64>]) -> Self {
        let turns = transfer.iter().map(quarter_turns).collect();
        let mut edge_tris = vec![[NONE; 2]; s.edges.len()];
        let tri_edges = s
            .tris
            .iter()
            .enumerate()
            .map(|(ti, tri)| {
                [0, 1, 2].map(|k| {
                    let e = s.edge(tri[k], tri[(k + 1) % 3]);
                    let slot = if edge_tris[e][0] == NONE { 0 } else { 1 };
                    edge_tris[e][slot] = ti;
                    e
                })
            })
            .collect();
        Self {
            s,
            turns,
            tri_edges,
            edge_tris,
        }
    }

    /// Maps vectors in `b`'s frame to `a`'s frame (a, b adjacent or equal).
    fn frame_map(&self, a: usize, b: usize) -> Rot {
        if a == b {
            return Rot(0);
        }
        let e = self.s.edge(a, b);
        if a < b {
            self.turns[e]
        } else {
            self.turns[e].inv()
        }
    }

    /// [`Self::frame_map`] for the ends of a known edge `e`.
    fn frame_map_on(&self, a: usize, b: usize, e: usize) -> Rot {
        if a < b {
            self.turns[e]
        } else {
            self.turns[e].inv()
        }
    }

    /// The triangle across edge `e` from triangle `t`, or [`NONE`] on the boundary.
    fn across(&self, t: usize, e: usize) -> usize {
        let [first, second] = self.edge_tris[e];
        if first == t { second } else { first }
    }

    /// Lattice step from `x` to `y` (the ends of edge `e`), in `x`'s frame.
    fn step_on(&self, m: &[[i64; 2]], x: usize, y: usize, e: usize) -> [i64; 2] {
        if x < y {
            m[e]
        } else {
            let v = self.frame_map_on(x, y, e).apply(m[e]);
            [-v[0], -v[1]]
        }
    }

    /// True when the cross field turns around triangle `t` (a field singularity).
    pub(crate) fn is_cone(&self, t: usize) -> bool {
        let [a, b, c] = self.s.tris[t];
        let [eab, ebc, eca] = self.tri_edges[t];
        (self.frame_map_on(a, b, eab).0
            + self.frame_map_on(b, c, ebc).0
            + self.frame_map_on(c, a, eca).0)
            % 4
            != 0
    }

    /// Number of dislocations of the jumps `m`: triangles that are not cones of the field and
    /// around which the lattice steps do not close.
    pub(crate) fn dislocations(&self, m: &[[i64; 2]]) -> usize {
        (0..self.s.tris.len())
            .filter(|&t| !self.is_cone(t) && self.curl(m, t) != [0, 0])
            .count()
    }

    /// Sum of lattice steps around triangle `t`, in the frame of its first vertex.
    fn curl(&self, m: &[[i64; 2]], t: usize) -> [i64; 2] {
        let [a, b, c] = self.s.tris[t];
        let [eab, ebc, eca] = self.tri_edges[t];
        let s1 = self.step_on(m, a, b, eab);
        let s2 = self
            .frame_map_on(a, b, eab)
            .apply(self.step_on(m, b, c, ebc));
        let s3 = self
            .frame_map_on(a, c, eca)
            .apply(self.step_on(m, c, a, eca));
        [s1[0] + s2[0] + s3[0], s1[1] + s2[1] + s3[1]]
    }

    /// The change of edge `e`'s jump that zeroes the curl of triangle `t` (which has `e`).
    fn cancelling_delta(&self, m: &[[i64; 2]], t: usize, e: usize) -> [i64; 2] {
        let tri = self.s.tris[t];
        let [x, y] = self.s.edges[e];
        let forward = (0..3).any(|k| tri[k] == x && tri[(k + 1) % 3] == y);
        let c = self.curl(m, t);
        let wanted = if forward { [-c[0], -c[1]] } else { c };
        self.frame_map(tri[0], x).inv().apply(wanted)
    }

    /// True when the dislocation at triangle `start` is one the lattice is better without.
    /// Over the triangles within `radius` steps of it, `B` (the sum of `density`) is what the
    /// surface and the field ask for and `D` (the sum of the integer curls) what the lattice
    /// has. The dislocation, of Burgers vector `b`, is unwanted when the patch asks for less
    /// than [`CALM`] and taking `b` out brings `D` nearer to `B` (`|D - b - B| < |D - B|`).
    /// One left over from the first lattice sits in a calm patch; the dislocations a bend or a
    /// turn of the designer's field needs sit where `B` is a Burgers vector or more.
    fn unwanted(&self, m: &[[i64; 2]], start: usize, density: &[[f64; 2]], radius: usize) -> bool {
        let b = self.curl(m, start);
        let mut seen: BTreeMap<usize, Rot> = BTreeMap::from([(start, Rot(0))]);
        let mut queue = VecDeque::from([(start, 0)]);
        let (mut d, mut want) = ([0i64; 2], [0f64; 2]);
        while let Some((t, level)) = queue.pop_front() {
            let to_start = seen[&t];
            let c = to_start.apply(self.curl(m, t));
            let w = to_start.apply(density[t]);
            for k in 0..2 {
                d[k] += c[k];
                want[k] += w[k];
            }
            if level == radius {
                continue;
            }
            for &e in &self.tri_edges[t] {
                let other = self.across(t, e);
                if other == NONE || self.is_cone(other) || seen.contains_key(&other) {
                    continue;
                }
                // Frames of the two first vertices, through a vertex both triangles share.
                let shared = self.s.edges[e][0];
                let (f1, f2) = (self.s.tris[t][0], self.s.tris[other][0]);
                let map = self.frame_map(f1, shared).then(self.frame_map(shared, f2));
                seen.insert(other, to_start.then(map));
                queue.push_back((other, level + 1));
            }
        }
        let off = |x: [f64; 2]| x[0] * x[0] + x[1] * x[1];
        let with = [d[0] as f64 - want[0], d[1] as f64 - want[1]];
        let without = [with[0] - b[0] as f64, with[1] - b[1] as f64];
        d == b && off(want) < CALM * CALM && off(without) < off(with)
    }

    /// Moves curls onto opposite curls along dual paths of at most `depth` triangles, or out
    /// through the boundary within `exit_depth` triangles. With `far = Some((far_depth,
    /// density, radius))`, a curl with neither within reach leaves through the boundary within
    /// `far_depth` triangles too, if [`Self::unwanted`] says so. `pinned_normal[v]` says the
    /// boundary vertex `v` has its lattice line pinned along the boundary (then only
    /// tangential steps may leave there). Returns how many defects were removed.
    /// `keep_going` is asked now and then; `false` stops with the defects left so far.
    pub fn cancel(
        &self,
        m: &mut [[i64; 2]],
        depth: usize,
        exit_depth: usize,
        far: Option<(usize, &[[f64; 2]], usize)>,
        pinned_normal: &[bool],
        keep_going: &mut dyn FnMut() -> bool,
    ) -> usize {
        let nt = self.s.tris.len();
        let cone: Vec<bool> = (0..nt).map(|t| self.is_cone(t)).collect();
        let far_depth = far.map_or(0, |f| f.0);
        let reach = depth.max(exit_depth).max(far_depth);
        let mut removed = 0;
        let mut level = vec![usize::MAX; nt];
        let mut parent = vec![(NONE, NONE); nt];
        let mut stamp = vec![usize::MAX; nt];
        for start in 0..nt {
            if cone[start] || self.curl(m, start) == [0, 0] {
                continue;
            }
            if !keep_going() {
                break;
            }
            // Breadth-first search over non-cone triangles.
            stamp[start] = start;
            level[start] = 0;
            parent[start] = (NONE, NONE);
            let mut queue = VecDeque::from([start]);
            let mut done = false;
            // Asked once, when the search first goes beyond `exit_depth`.
            let mut may_leave_far: Option<bool> = None;
            while let Some(t) = queue.pop_front() {
                if done {
                    break;
                }
                for &e in &self.tri_edges[t] {
                    let other = self.across(t, e);
                    if other == NONE {
                        // Boundary exit, only near the boundary: far from it a lone
                        // dislocation is usually one the geometry needs (the inside of a
                        // bend has fewer rows than the outside), and removing it would
                        // stretch every quad in between.
                        let within = level[t] <= exit_depth
                            || (level[t] <= far_depth
                                && *may_leave_far.get_or_insert_with(|| {
                                    far.is_some_and(|(_, density, radius)| {
                                        self.unwanted(m, start, density, radius)
                                    })
                                }));
                        if within && self.try_path(m, start, t, &parent, Some(e), pinned_normal) {
                            removed += 1;
                            done = true;
                            break;
                        }
                        continue;
                    }
                    if cone[other] || stamp[other] == start || level[t] + 1 > reach {
                        continue;
                    }
                    stamp[other] = start;
                    level[other] = level[t] + 1;
                    parent[other] = (t, e);
                    if level[other] <= depth
                        && self.curl(m, other) != [0, 0]
                        && self.try_path(m, start, other, &parent, None, pinned_normal)
                    {
                        removed += 2;
                        done = true;
                        break;
                    }
                    queue.push_back(other);
                }
            }
        }
        removed
    }

    /// Walks the curl of `start` to `end` along `parent` links (and out through boundary
    /// edge `exit`, if given); keeps the change only if it cancels.
    fn try_path(
        &self,
        m: &mut [[i64; 2]],
        start: usize,
        end: usize,
        parent: &[(usize, usize)],
        exit: Option<usize>,
        pinned_normal: &[bool],
    ) -> bool {
        let mut path = vec![end];
        let mut edges = Vec::new();
        let mut t = end;
        while t != start {
            let (p, e) = parent[t];
            if p == NONE {
                return false;
            }
            edges.push(e);
            path.push(p);
            t = p;
        }
        path.reverse();
        edges.reverse();
        let mut log: Vec<(usize, [i64; 2])> = Vec::new();
        for (k, &e) in edges.iter().enumerate() {
            let d = self.cancelling_delta(m, path[k], e);
            m[e] = [m[e][0] + d[0], m[e][1] + d[1]];
            log.push((e, d));
        }
        let ok = match exit {
            None => self.curl(m, end) == [0, 0],
            Some(e) => {
                let d = self.cancelling_delta(m, end, e);
                let [x, y] = self.s.edges[e];
                let allowed = !(pinned_normal[x] && pinned_normal[y]) || d[1] == 0;
                if allowed {
                    m[e] = [m[e][0] + d[0], m[e][1] + d[1]];
                    log.push((e, d));
                }
                allowed && self.curl(m, end) == [0, 0]
            }
        };
        if !ok {
            for (e, d) in log.into_iter().rev() {
                m[e] = [m[e][0] - d[0], m[e][1] - d[1]];
            }
        }
        ok
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::surface::samples::sheet;
    use nalgebra::Vector3;

    /// A flat `n` x `n` grid of unit cells, two triangles each, with one frame everywhere and
    /// the lattice steps of a perfect unit lattice (no curl anywhere).
    fn grid(n: usize) -> (Surface, Vec<Matrix2<f64>>, Vec<[i64; 2]>) {
        let s = sheet(n, 1.0, (0..0, 0..0), |_, _| 0.0);
        let transfer = vec![Matrix2::identity(); s.edges.len()];
        let m = s
            .edges
            .iter()
            .map(|&[a, b]| {
                let d = s.pos[b] - s.pos[a];
                [d.x.round() as i64, d.y.round() as i64]
            })
            .collect();
        (s, transfer, m)
    }

    /// Gives the triangle on the bottom boundary edge from `x` to `x + 1` a dislocation, and
    /// returns the triangle.
    fn dislocate(s: &Surface, jumps: &Jumps, m: &mut [[i64; 2]], x: usize) -> usize {
        let at = |x: usize| {
            (0..s.len())
                .find(|&v| s.pos[v] == Vector3::new(x as f64, 0.0, 0.0))
                .expect("a vertex on the bottom edge")
        };
        let e = s.edge(at(x), at(x + 1));
        m[e][0] += 1;
        let [t, other] = jumps.edge_tris[e];
        assert_eq!(other, NONE, "a boundary edge");
        assert_ne!(jumps.curl(m, t), [0, 0]);
        t
    }

    #[test]
    fn transfers_round_to_the_nearest_quarter_turn() {
        let turn = |deg: f64| {
            let a = deg.to_radians();
            Matrix2::new(a.cos(), -a.sin(), a.sin(), a.cos())
        };
        for (deg, want) in [(10.0, 0.0), (80.0, 90.0), (-100.0, -90.0), (170.0, 180.0)] {
            assert!(
                (quarter_turn_matrix(&turn(deg)) - turn(want)).norm() < 1e-12,
                "{deg}"
            );
        }
    }

    #[test]
    fn a_lone_dislocation_in_a_calm_patch_is_unwanted_and_a_wanted_or_crowded_one_is_not() {
        let (s, transfer, mut m) = grid(8);
        let jumps = Jumps::new(&s, &transfer);
        let nt = s.tris.len();
        assert!((0..nt).all(|t| jumps.curl(&m, t) == [0, 0]));
        assert_eq!(jumps.dislocations(&m), 0);
        // The bottom edge of the fourth cell.
        let start = dislocate(&s, &jumps, &mut m, 3);
        assert_eq!(jumps.dislocations(&m), 1);
        let b = jumps.curl(&m, start);
        let calm = vec![[0.0; 2]; nt];
        assert!(jumps.unwanted(&m, start, &calm, 3));
        // The surface asks for this Burgers vector here: it stays.
        let mut asked = calm.clone();
        asked[start] = [b[0] as f64, b[1] as f64];
        assert!(!jumps.unwanted(&m, start, &asked, 3));
        // A second one of the same sign next to it: a row end the shape is making, it stays.
        let next = dislocate(&s, &jumps, &mut m, 4);
        assert_eq!(jumps.curl(&m, next), b);
        assert!(!jumps.unwanted(&m, start, &calm, 3));
        // Beyond the patch's radius the neighbour no longer counts.
        let (s, transfer, mut m) = grid(8);
        let jumps = Jumps::new(&s, &transfer);
        let start = dislocate(&s, &jumps, &mut m, 0);
        dislocate(&s, &jumps, &mut m, 7);
        assert!(jumps.unwanted(&m, start, &calm, 3));
    }
}
