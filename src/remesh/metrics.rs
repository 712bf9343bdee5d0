//! Acceptance numbers of a quad mesh against its input surface and target edge, so our
//! remesher and foreign ones (QuadriFlow, Instant Meshes) are judged by the same ruler.

use nalgebra::Vector3;
use serde::Serialize;

use super::surface::Locator;
use crate::mesh::PolyMesh;

/// Quality of a quad mesh for tiling at target edge `t` (all ratios are fractions, 1 = 100%).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Metrics {
    /// Number of faces.
    pub faces: usize,
    /// Every face has four corners (only quads pair into tiles).
    pub pure_quad: bool,
    /// Interior vertices with other than four edges: each is an irregular tile spot.
    pub interior_irregular_vertices: usize,
    /// Boundary vertices farther than 0.05 t from the input boundary (a ragged or dropped
    /// strip along the shell's edge).
    pub boundary_vertices_off_input: usize,
    /// Mean edge length over `t`.
    pub mean_edge_ratio: f64,
    /// Fraction of edges within 20% of `t`.
    pub edges_within_20pct: f64,
    /// Fraction of faces whose area is within 20% of `t^2`.
    pub faces_area_within_20pct: f64,
    /// 95th percentile of |corner angle - 90 degrees| over corners at interior vertices.
    pub p95_corner_angle_deviation_deg: f64,
    /// Largest distance of a vertex, edge midpoint or face centroid to the input, over `t`.
    pub max_distance_to_input_ratio: f64,
    /// Fraction of the input area lying within 0.1 t of the quad mesh.
    pub area_covered_ratio: f64,
    /// Wall-clock seconds of the remesh itself, without measuring these metrics (0 when
    /// measured on a foreign mesh).
    pub seconds: f64,
    /// The sheets between the surface's creases that the remesh quadrangulated each on its
    /// own (a groin vault's four webs; `mesh::crease`), or 0 when no crease parts the surface
    /// (and when measured on a foreign mesh).
    pub crease_sheets: usize,
    /// Vertices of an input much finer than the quads removed before remeshing, 0 when it
    /// was remeshed as given (`mesh::simplify`; `pipeline`'s tries, which tile the
    /// simplified surface).
    pub input_vertices_removed: usize,
    /// The lattice was solved again from a coarse start because the first one came out
    /// stretched (`remesh::position`'s coarse start): the field asks rows to end all over
    /// the surface (the rings of a dome of revolution, a bell), where each row end costs
    /// tiles cut. False when measured on a foreign mesh.
    pub coarse_start: bool,
    /// Some boundary loop was followed: its crosses pinned to the boundary's tangents and a
    /// lattice line laid on it ([`crate::remesh::BoundaryAlignment`]; `Auto` follows the
    /// loops with corners). False when no loop was (a dome's round rim under `Auto`, `Never`)
    /// and when measured on a foreign mesh.
    pub aligned_boundary: bool,
}

/// Measures `quads` against `input` at target edge `t`; works on any polygon mesh, e.g.
/// QuadriFlow's output, so the acceptance table compares like with like.
pub fn metrics(input: &PolyMesh, quads: &PolyMesh, target_edge: f64) -> Metrics {
    let locator = Locator::from_polymesh(input);
    metrics_with(&locator, input, quads, target_edge)
}

/// [`metrics`] with a locator on the input already built.
pub(crate) fn metrics_with(
    locator: &Locator,
    input: &PolyMesh,
    quads: &PolyMesh,
    t: f64,
) -> Metrics {
    let pos: Vec<Vector3<f64>> = quads.positions().iter().map(|p| p.coords).collect();
    let faces = quads.faces();
    let n = pos.len();
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for f in faces {
        for i in 0..f.len() {
            let (a, b) = (f[i], f[(i + 1) % f.len()]);
            edges.push((a.min(b), a.max(b)));
        }
    }
    edges.sort_unstable();
    // Count faces per edge from the sorted multiset, then dedup.
    let mut unique: Vec<((usize, usize), usize)> = Vec::new();
    for e in edges {
        match unique.last_mut() {
            Some((last, count)) if *last == e => *count += 1,
            _ => unique.push((e, 1)),
        }
    }
    let mut valence = vec![0usize; n];
    let mut boundary = vec![false; n];
    for &((a, b), count) in &unique {
        valence[a] += 1;
        valence[b] += 1;
        if count == 1 {
            boundary[a] = true;
            boundary[b] = true;
        }
    }
    let used: Vec<bool> = {
        let mut u = vec![false; n];
        faces.iter().flatten().for_each(|&v| u[v] = true);
        u
    };
    let interior_irregular_vertices = (0..n)
        .filter(|&v| used[v] && !boundary[v] && valence[v] != 4)
        .count();
    let boundary_vertices_off_input = (0..n)
        .filter(|&v| boundary[v])
        .filter(|&v| {
            locator
                .closest_boundary(&pos[v])
                .is_none_or(|q| (q - pos[v]).norm() > 0.05 * t)
        })
        .count();

    let lengths: Vec<f64> = unique
        .iter()
        .map(|&((a, b), _)| (pos[a] - pos[b]).norm() / t)
        .collect();
    let mean_edge_ratio = if lengths.is_empty() {
        0.0
    } else {
        lengths.iter().sum::<f64>() / lengths.len() as f64
    };
    let edges_within_20pct = within_20pct(&lengths);
    let faces_area_within_20pct = fraction(
        (0..faces.len()).map(|f| (quads.face_area_vector(f).norm() / (t * t) - 1.0).abs() <= 0.2),
    );

    let mut deviations: Vec<f64> = Vec::new();
    for f in faces {
        let k = f.len();
        for i in 0..k {
            let v = f[i];
            if boundary[v] {
                continue;
            }
            let a = pos[f[(i + k - 1) % k]] - pos[v];
            let b = pos[f[(i + 1) % k]] - pos[v];
            deviations.push((a.angle(&b).to_degrees() - 90.0).abs());
        }
    }
    deviations.sort_by(f64::total_cmp);
    let p95_corner_angle_deviation_deg = if deviations.is_empty() {
        0.0
    } else {
        deviations
            [((deviations.len() as f64 * 0.95).ceil() as usize).clamp(1, deviations.len()) - 1]
    };

    // Closest-point queries, each on its own (on the threads of `parallel`), folded in order.
    let farthest = |count: usize, point: &(dyn Fn(usize) -> Vector3<f64> + Sync)| {
        crate::parallel::map(count, |i| locator.distance(&point(i)))
            .into_iter()
            .fold(0.0, f64::max)
    };
    let max_distance = farthest(pos.len(), &|v| pos[v])
        .max(farthest(unique.len(), &|e| {
            let ((a, b), _) = unique[e];
            (pos[a] + pos[b]) * 0.5
        }))
        .max(farthest(faces.len(), &|f| quads.face_centroid(f).coords));

    // Coverage: sample every input triangle and ask how far the quad mesh is.
    let quad_locator = Locator::from_polymesh(quads);
    let input_faces = input.faces();
    let samples = crate::parallel::map(input_faces.len(), |f| {
        let face = &input_faces[f];
        let mut found = Vec::with_capacity(3 * face.len());
        for k in 1..face.len() - 1 {
            let [a, b, c] = [face[0], face[k], face[k + 1]].map(|v| input.positions()[v].coords);
            let area = (b - a).cross(&(c - a)).norm() * 0.5;
            let centre = (a + b + c) / 3.0;
            for corner in [a, b, c] {
                let sample = centre * 0.6 + corner * 0.4;
                let (q, _) = quad_locator.closest(&sample);
                found.push((area / 3.0, (q - sample).norm() <= 0.1 * t));
            }
        }
        found
    });
    let mut covered = 0.0;
    let mut total = 0.0;
    for &(area, hit) in samples.iter().flatten() {
        total += area;
        if hit {
            covered += area;
        }
    }
    let area_covered_ratio = if total > 0.0 { covered / total } else { 0.0 };

    Metrics {
        faces: faces.len(),
        pure_quad: faces.iter().all(|f| f.len() == 4),
        interior_irregular_vertices,
        boundary_vertices_off_input,
        mean_edge_ratio,
        edges_within_20pct,
        faces_area_within_20pct,
        p95_corner_angle_deviation_deg,
        max_distance_to_input_ratio: max_distance / t,
        area_covered_ratio,
        seconds: 0.0,
        crease_sheets: 0,
        input_vertices_removed: 0,
        coarse_start: false,
        aligned_boundary: false,
    }
}

/// Share of the quad mesh's edges (each counted once) within 20 % of `t`: the remesher's
/// promise, and what the tile checks ask of quads made elsewhere
/// ([`crate::report::warnings`]).
pub fn edges_within_20pct(quads: &PolyMesh, t: f64) -> f64 {
    let pos = quads.positions();
    let mut edges: Vec<(usize, usize)> = quads
        .faces()
        .iter()
        .flat_map(|f| (0..f.len()).map(move |i| (f[i], f[(i + 1) % f.len()])))
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    let lengths: Vec<f64> = edges
        .iter()
        .map(|&(a, b)| (pos[a] - pos[b]).norm() / t)
        .collect();
    within_20pct(&lengths)
}

/// Share of `ratios` (edge length over `t`) within 20 % of 1.
fn within_20pct(ratios: &[f64]) -> f64 {
    fraction(ratios.iter().map(|l| (l - 1.0).abs() <= 0.2))
}

fn fraction(flags: impl Iterator<Item = bool>) -> f64 {
    let (mut yes, mut all) = (0usize, 0usize);
    for f in flags {
        all += 1;
        yes += usize::from(f);
    }
    if all == 0 {
        0.0
    } else {
        yes as f64 / all as f64
    }
}
