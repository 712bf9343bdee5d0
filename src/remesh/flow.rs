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

use std::collections::VecDeque;

use nalgebra::Matrix2;

use super::surface::Surface;

/// Quarter turns counter-clockwise.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Rot(u8);

impl Rot {
    fn apply(self, v: [i64; 2]) -> [i64; 2] {
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
}

/// Rounds a frame transfer matrix to the nearest quarter turn.
fn quarter_turns(t: &Matrix2<f64>) -> Rot {
    let angle = (t[(1, 0)] - t[(0, 1)]).atan2(t[(0, 0)] + t[(1, 1)]);
    Rot(((angle / std::f64::consts::FRAC_PI_2).round() as i64).rem_euclid(4) as u8)
}

/// Lattice jumps with the connectivity to reason about their curls.
pub(crate) struct Jumps<'a> {
    s: &'a Surface,
    turns: Vec<Rot>,
    tri_edges: Vec<[usize; 3]>,
    edge_tris: Vec<[usize; 2]>,
}

const NONE: usize = usize::MAX;

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
                    let e = edge_id(s, tri[k], tri[(k + 1) % 3]);
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
        let e = edge_id(self.s, a, b);
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
    fn is_cone(&self, t: usize) -> bool {
        let [a, b, c] = self.s.tris[t];
        let [eab, ebc, eca] = self.tri_edges[t];
        (self.frame_map_on(a, b, eab).0
            + self.frame_map_on(b, c, ebc).0
            + self.frame_map_on(c, a, eca).0)
            % 4
            != 0
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

    /// Moves curls onto opposite curls along dual paths of at most `depth` triangles, or out
    /// through the boundary within `exit_depth` triangles. `pinned_normal[v]` says the boundary vertex `v` has its
    /// lattice line pinned along the boundary (then only tangential steps may leave there).
    /// Returns how many defects were removed.
    /// `keep_going` is asked now and then; `false` stops with the defects left so far.
    pub fn cancel(
        &self,
        m: &mut [[i64; 2]],
        depth: usize,
        exit_depth: usize,
        pinned_normal: &[bool],
        keep_going: &mut dyn FnMut() -> bool,
    ) -> usize {
        let nt = self.s.tris.len();
        let cone: Vec<bool> = (0..nt).map(|t| self.is_cone(t)).collect();
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
            while let Some(t) = queue.pop_front() {
                if done {
                    break;
                }
                for &e in &self.tri_edges[t] {
                    let other = if self.edge_tris[e][0] == t {
                        self.edge_tris[e][1]
                    } else {
                        self.edge_tris[e][0]
                    };
                    if other == NONE {
                        // Boundary exit, only near the boundary: far from it a lone
                        // dislocation is usually one the geometry needs (the inside of a
                        // bend has fewer rows than the outside), and removing it would
                        // stretch every quad in between.
                        if level[t] <= exit_depth
                            && self.try_path(m, start, t, &parent, Some(e), pinned_normal)
                        {
                            removed += 1;
                            done = true;
                            break;
                        }
                        continue;
                    }
                    if cone[other] || stamp[other] == start || level[t] + 1 > depth {
                        continue;
                    }
                    stamp[other] = start;
                    level[other] = level[t] + 1;
                    parent[other] = (t, e);
                    if self.curl(m, other) != [0, 0]
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

/// The edge id joining `a` and `b` (which must be adjacent).
fn edge_id(s: &Surface, a: usize, b: usize) -> usize {
    let list = &s.adj[a];
    let k = list.partition_point(|&(v, _)| v < b);
    list[k].1
}
