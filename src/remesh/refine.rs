//! Refinement of the working surface for the position field: Instant Meshes samples the
//! lattice on vertices, so edges must be clearly shorter than `t`: midpoint subdivision, then
//! bisection of any edge still longer than 3/4 t, as slivers have.

use nalgebra::Vector3;

use super::field::{Principal, match_rosy};
use super::surface::{Surface, in_tangent_plane};
use super::user_field::Samples;

/// The midpoint of edge `a`-`b` of `surface` with its normal and cross frame (`frames[a]`
/// averaged with `frames[b]` turned to match it), for refining the working surface.
fn edge_midpoint(
    surface: &Surface,
    frames: &[Vector3<f64>],
    a: usize,
    b: usize,
) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    let n = (surface.normals[a] + surface.normals[b])
        .try_normalize(1e-300)
        .unwrap_or(surface.normals[a]);
    let o = frames[a] + match_rosy(&frames[a], &frames[b], &surface.normals[b]);
    let o = in_tangent_plane(&o, &n);
    ((surface.pos[a] + surface.pos[b]) * 0.5, n, o)
}

/// Midpoint-subdivides `base` (flat, so the surface does not move) until the mean edge is at
/// most `t / 2`, interpolating the orientation field `frames` (one tangent vector per vertex,
/// a 4-RoSy representative) and the normals onto the new vertices.
pub(crate) fn refine(
    base: &Surface,
    frames: &[Vector3<f64>],
    t: f64,
) -> (Surface, Vec<Vector3<f64>>) {
    let limit = 3_000_000usize;
    let mut surface = base.clone();
    let mut frames = frames.to_vec();
    while surface.mean_edge > t / 2.0
        && surface.tris.len() * 4 <= limit
        && !fine_already(&surface, t / 4.0)
    {
        (surface, frames) = split_edges(&surface, &frames, |_| true);
    }
    // Slivers (long thin triangles, common where a coarse mesh was subdivided around a
    // support) keep edges far longer than the mean: the lattice cannot be read across an edge
    // several quads long, so such edges are bisected until none is.
    let long = LONG_EDGE * t;
    while surface.tris.len() * 2 <= limit {
        let marked: Vec<bool> = surface
            .edges
            .iter()
            .map(|&[a, b]| (surface.pos[a] - surface.pos[b]).norm() > long)
            .collect();
        if !marked.iter().any(|&m| m) {
            break;
        }
        (surface, frames) = split_edges(&surface, &frames, |e| marked[e]);
    }
    surface.set_boundary_scale(t * 0.5);
    (surface, frames)
}

/// A coarse input midpoint-subdivided for the orientation field: the fine surface and, per
/// fine vertex, the coarse vertices it lies between with their weights (linear
/// interpolation along the coarse triangles; an original vertex is itself with weight 1).
pub(crate) struct Subdivision {
    /// The subdivided surface (the same flat triangles as the coarse one).
    pub surface: Surface,
    /// Per fine vertex, coarse vertices and weights summing to 1.
    pub parents: Vec<Vec<(usize, f64)>>,
}

impl Subdivision {
    /// Per-vertex data of the coarse surface (a designer's vectors, guide samples) carried to
    /// the fine vertices, each sample's weight times its parent's.
    pub fn spread(&self, coarse: &Samples) -> Samples {
        self.parents
            .iter()
            .map(|parents| {
                parents
                    .iter()
                    .flat_map(|&(c, w)| coarse[c].iter().map(move |&(d, sw)| (d, sw * w)))
                    .collect()
            })
            .collect()
    }

    /// The coarse surface's principal curvatures interpolated onto the fine vertices: the
    /// parents' directions matched as crosses to the first one and averaged by weight,
    /// anisotropy and mean curvature averaged (a vertex none of whose parents has a
    /// curvature has none).
    pub fn spread_principal(&self, coarse: &[Option<Principal>]) -> Vec<Option<Principal>> {
        self.parents
            .iter()
            .enumerate()
            .map(|(v, parents)| {
                let n = self.surface.normals[v];
                let known: Vec<(Principal, f64)> = parents
                    .iter()
                    .filter_map(|&(c, w)| coarse[c].map(|p| (p, w)))
                    .collect();
                let (first, _) = *known.first()?;
                let total: f64 = known.iter().map(|&(_, w)| w).sum();
                let mut dir = Vector3::zeros();
                let mut local_dir = Vector3::zeros();
                let (mut aniso, mut mean) = (0.0, 0.0);
                for &(p, w) in &known {
                    dir += match_rosy(&first.dir, &p.dir, &n) * w;
                    local_dir += match_rosy(&first.local_dir, &p.local_dir, &n) * w;
                    aniso += p.aniso * w / total;
                    mean += p.mean * w / total;
                }
                Some(Principal {
                    dir: in_tangent_plane(&dir, &n),
                    local_dir: in_tangent_plane(&local_dir, &n),
                    aniso,
                    mean,
                })
            })
            .collect()
    }
}

/// Midpoint-subdivides a coarse `base` (flat: the surface does not move) until its mean edge
/// is at most `t`, so that the orientation field is solved at about the lattice's resolution
/// whatever the input's (a coarse render mesh of a smooth shell, faces of several tiles);
/// `None` when `base` is already that fine. The field's data (curvature, a designer's
/// vectors, guides) stay those of the coarse vertices, interpolated ([`Subdivision`]): the
/// coarse vertices are where the input samples its shape, midpoints on flat faces would read
/// the facets as curvature.
pub(crate) fn subdivide_coarse(base: &Surface, t: f64) -> Option<Subdivision> {
    let limit = 3_000_000usize;
    let mut fine: Option<Subdivision> = None;
    loop {
        let current = fine.as_ref().map_or(base, |f| &f.surface);
        if current.mean_edge <= t
            || current.tris.len() * 4 > limit
            || fine_already(current, t / 2.0)
        {
            break;
        }
        let mut parents = fine.as_ref().map_or_else(
            || (0..base.len()).map(|v| vec![(v, 1.0)]).collect(),
            |f| f.parents.clone(),
        );
        // `split_edges` appends the midpoints in edge order.
        for &[a, b] in &current.edges {
            let mut mid: Vec<(usize, f64)> = Vec::with_capacity(4);
            for &(c, w) in parents[a].iter().chain(&parents[b]) {
                match mid.iter_mut().find(|(d, _)| *d == c) {
                    Some((_, m)) => *m += w / 2.0,
                    None => mid.push((c, w / 2.0)),
                }
            }
            parents.push(mid);
        }
        let frames = vec![Vector3::zeros(); current.len()];
        let surface = split_edges(current, &frames, |_| true).0;
        fine = Some(Subdivision { surface, parents });
    }
    fine
}

/// Splits the edges `e` of `surface` for which `split(e)` holds at their midpoints (see
/// [`edge_midpoint`]), with the field `frames`: a triangle with all three edges split becomes
/// four, with one two, with two a corner triangle and two more cut along the shorter
/// diagonal.
fn split_edges(
    surface: &Surface,
    frames: &[Vector3<f64>],
    split: impl Fn(usize) -> bool,
) -> (Surface, Vec<Vector3<f64>>) {
    let mut pos = surface.pos.clone();
    let mut normals = surface.normals.clone();
    let mut fine_frames = frames.to_vec();
    let mut mid = vec![usize::MAX; surface.edges.len()];
    for (e, &[a, b]) in surface.edges.iter().enumerate() {
        if !split(e) {
            continue;
        }
        mid[e] = pos.len();
        let (p, n, o) = edge_midpoint(surface, frames, a, b);
        pos.push(p);
        normals.push(n);
        fine_frames.push(o);
    }
    let mid_of = |a: usize, b: usize| -> usize { mid[surface.edge(a, b)] };
    let mut tris = Vec::with_capacity(surface.tris.len() * 4);
    for &tri in &surface.tris {
        let m = [0, 1, 2].map(|k| mid_of(tri[k], tri[(k + 1) % 3]));
        let count = m.iter().filter(|&&x| x != usize::MAX).count();
        match count {
            0 => tris.push(tri),
            3 => {
                let [a, b, c] = tri;
                let [ab, bc, ca] = m;
                tris.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
            }
            _ => {
                // Rotate so the first split edge is tri[0]-tri[1].
                let k = (0..3)
                    .find(|&k| m[k] != usize::MAX && (count == 1 || m[(k + 1) % 3] != usize::MAX))
                    .unwrap_or(0);
                let (a, b, c) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
                let (ab, bc) = (m[k], m[(k + 1) % 3]);
                if count == 1 {
                    tris.extend([[a, ab, c], [ab, b, c]]);
                } else {
                    // Edges ab and bc split: corner triangle at b, the rest cut along the
                    // shorter diagonal.
                    tris.push([ab, b, bc]);
                    if (pos[ab] - pos[c]).norm() <= (pos[bc] - pos[a]).norm() {
                        tris.extend([[a, ab, c], [ab, bc, c]]);
                    } else {
                        tris.extend([[a, ab, bc], [a, bc, c]]);
                    }
                }
            }
        }
    }
    (Surface::build(pos, tris, Some(normals)), fine_frames)
}

/// Whether over a tenth of `surface`'s edges are at most `short` long: a mesh of very uneven
/// triangles (a fan, a coarse mesh refined around a support), which a uniform subdivision
/// would make needlessly fine where it is fine already (each level four times the triangles),
/// so that its long edges are bisected alone.
fn fine_already(surface: &Surface, short: f64) -> bool {
    let fine = surface
        .edges
        .iter()
        .filter(|&&[a, b]| (surface.pos[a] - surface.pos[b]).norm() <= short)
        .count();
    fine * 10 > surface.edges.len()
}

/// Longest edge of the working surface, as a fraction of the target edge.
const LONG_EDGE: f64 = 0.75;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::remesh::surface::{Locator, any_tangent};

    /// A fine patch of 20 x 20 cells of 0.05 on a saddle, with a fan of slivers over 2 units
    /// to one far point along its right edge: the mean edge is short, the slivers' are long.
    fn patch_with_slivers() -> Surface {
        let n = 20;
        let at = |i: usize, j: usize| j * (n + 1) + i;
        let mut pos: Vec<Vector3<f64>> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i as f64 * 0.05, j as f64 * 0.05)))
            .map(|(x, y)| Vector3::new(x, y, 0.2 * (x - 0.5) * (y - 0.5)))
            .collect();
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        pos.push(Vector3::new(3.0, 0.5, 0.3));
        let far = pos.len() - 1;
        for j in 0..n {
            tris.push([at(n, j + 1), at(n, j), far]);
        }
        Surface::build(pos, tris, None)
    }

    fn area(s: &Surface) -> f64 {
        s.tris
            .iter()
            .map(|&[a, b, c]| s.edge_vec(a, b).cross(&s.edge_vec(a, c)).norm() / 2.0)
            .sum()
    }

    #[test]
    fn a_coarse_surface_is_subdivided_with_its_parents() {
        // 2 x 2 cells of 1 on a saddle: mean edge over 1, subdivided twice for t = 0.3.
        let at = |i: usize, j: usize| j * 3 + i;
        let pos: Vec<Vector3<f64>> = (0..3)
            .flat_map(|j| (0..3).map(move |i| (i as f64, j as f64)))
            .map(|(x, y)| Vector3::new(x, y, 0.2 * (x - 1.0) * (y - 1.0)))
            .collect();
        let mut tris = Vec::new();
        for j in 0..2 {
            for i in 0..2 {
                tris.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                tris.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let coarse = Surface::build(pos, tris, None);
        assert!(subdivide_coarse(&coarse, 2.0).is_none());
        let sub = subdivide_coarse(&coarse, 0.3).unwrap();
        assert!(sub.surface.mean_edge <= 0.3);
        assert_eq!(sub.surface.tris.len(), coarse.tris.len() * 16);
        for (v, parents) in sub.parents.iter().enumerate() {
            // Weights sum to 1, at most a triangle's corners, and place the vertex.
            let total: f64 = parents.iter().map(|&(_, w)| w).sum();
            assert!((total - 1.0).abs() < 1e-12 && parents.len() <= 3);
            let p: Vector3<f64> = parents.iter().map(|&(c, w)| coarse.pos[c] * w).sum();
            assert!((p - sub.surface.pos[v]).norm() < 1e-12);
        }
        // Data of the coarse vertices is spread by weight.
        let samples: Samples = (0..coarse.len())
            .map(|v| vec![(Vector3::x(), v as f64)])
            .collect();
        let spread = sub.spread(&samples);
        for (v, parents) in sub.parents.iter().enumerate() {
            let want: f64 = parents.iter().map(|&(c, w)| c as f64 * w).sum();
            let got: f64 = spread[v].iter().map(|&(_, w)| w).sum();
            assert!((want - got).abs() < 1e-12);
        }
    }

    #[test]
    fn refinement_keeps_every_edge_below_three_quarters_of_t_and_the_surface_in_place() {
        let base = patch_with_slivers();
        let frames: Vec<Vector3<f64>> = base.normals.iter().map(any_tangent).collect();
        let on_base = Locator::new(&base);
        let longest = |s: &Surface| {
            s.edges
                .iter()
                .map(|&[a, b]| s.edge_vec(a, b).norm())
                .fold(0.0, f64::max)
        };
        assert!(longest(&base) > 2.0);
        // t = 0.4: the mean edge is short enough already, only the slivers are bisected;
        // t = 0.06: the whole surface is subdivided first.
        for t in [0.4, 0.06] {
            let (fine, fine_frames) = refine(&base, &frames, t);
            assert!(fine.tris.len() > base.tris.len());
            assert!(
                longest(&fine) <= LONG_EDGE * t,
                "t = {t}: longest edge {}",
                longest(&fine)
            );
            assert!(fine.mean_edge <= t / 2.0);
            // Flat subdivision: every vertex on the input, the same area and outline.
            assert!(fine.pos.iter().all(|p| on_base.distance(p) < 1e-12));
            assert!((area(&fine) - area(&base)).abs() < 1e-9 * area(&base));
            let outline = |s: &Surface| {
                s.boundary_loops()
                    .iter()
                    .map(|lp| lp.length)
                    .collect::<Vec<_>>()
            };
            let (a, b) = (outline(&fine), outline(&base));
            assert!(a.len() == 1 && b.len() == 1 && (a[0] - b[0]).abs() < 1e-9);
            // The field goes along: a unit tangent per vertex, the old ones unchanged.
            assert_eq!(fine_frames.len(), fine.len());
            assert_eq!(fine_frames[..frames.len()], frames[..]);
            for (o, n) in fine_frames.iter().zip(&fine.normals) {
                assert!(
                    (o.norm() - 1.0).abs() < 1e-9
                        && o.dot(n).abs() < 1e-9
                        && (n.norm() - 1.0).abs() < 1e-9
                );
            }
            // It comes back at the boundary scale of t: the patch's corners, the far tip.
            assert!(fine.corner.iter().any(|&c| c));
        }
    }

    #[test]
    fn a_fan_of_slivers_has_its_long_edges_bisected_not_every_triangle_split() {
        // 400 slivers of 3 around a point, their rim edges 0.047 long: the mean edge is half
        // the spokes'. Split uniformly until the mean was t / 2 it became 409,600 triangles;
        // now one level, then the long edges alone: 129,600.
        let n = 400;
        let mut pos = vec![Vector3::zeros()];
        pos.extend((0..n).map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let (x, y) = (3.0 * a.cos(), 3.0 * a.sin());
            Vector3::new(x, y, 0.05 * (x * x - y * y))
        }));
        let tris: Vec<[usize; 3]> = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
        let base = Surface::build(pos, tris, None);
        let frames: Vec<Vector3<f64>> = base.normals.iter().map(any_tangent).collect();
        let t = 0.145;
        let (fine, _) = refine(&base, &frames, t);
        let longest = fine
            .edges
            .iter()
            .map(|&[a, b]| fine.edge_vec(a, b).norm())
            .fold(0.0, f64::max);
        assert!(longest <= LONG_EDGE * t, "longest edge {longest}");
        assert!(fine.tris.len() < 200_000, "{} triangles", fine.tris.len());
    }

    #[test]
    fn a_surface_fine_enough_already_is_left_as_it_is() {
        let base = patch_with_slivers();
        let frames: Vec<Vector3<f64>> = base.normals.iter().map(any_tangent).collect();
        let (same, same_frames) = refine(&base, &frames, 4.0);
        assert_eq!(
            (same.pos, same.tris, same_frames),
            (base.pos, base.tris, frames)
        );
    }
}
