//! Area samples of a surface: each triangle cut into equal triangles no longer than a
//! spacing, each sample its small triangle's centroid weighted by its area. The report's
//! coverage and the tear fill of the tile stage read the surface through the same samples.

use nalgebra::Point3;

/// Samples across the smallest tile side: the sampling triangles' longest edges are at most
/// that side over this (70 mm for a 280 x 140 mm tile), finer than any gap worth seeing. The
/// coverage ([`crate::report::coverage`]) and the tear fill (`tiles::tears`) sample alike, so
/// every hole the coverage sees is tried.
pub(crate) const SAMPLES_PER_TILE_SIDE: f64 = 2.0;

/// Most sampling triangles along one edge of a triangle: a triangle is cut into at most this
/// squared samples (a 100 m face at a 70 mm spacing still reads in well under a second).
const MAX_SPLITS: usize = 1024;

/// Calls `visit` with the centroid and area of each of the `k * k` triangles of the regular
/// subdivision of triangle `t`, `k` the least number of splits per edge that keeps every
/// edge at most `spacing` long.
pub fn triangle(t: &[Point3<f64>; 3], spacing: f64, mut visit: impl FnMut(Point3<f64>, f64)) {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let area = e1.cross(&e2).norm() / 2.0;
    let longest = e1.norm().max(e2.norm()).max((t[2] - t[1]).norm());
    let k = if spacing > 0.0 && longest > spacing {
        ((longest / spacing).ceil() as usize).min(MAX_SPLITS)
    } else {
        1
    };
    let (kf, piece) = (k as f64, area / (k * k) as f64);
    for i in 0..k {
        for j in 0..k - i {
            // The triangle pointing the way of `t`, and the one turned over beside it.
            let (u, v) = ((i as f64 + 1.0 / 3.0) / kf, (j as f64 + 1.0 / 3.0) / kf);
            visit(t[0] + e1 * u + e2 * v, piece);
            if i + j + 1 < k {
                let (u, v) = ((i as f64 + 2.0 / 3.0) / kf, (j as f64 + 2.0 / 3.0) / kf);
                visit(t[0] + e1 * u + e2 * v, piece);
            }
        }
    }
}

/// Calls `visit` with the samples ([`triangle`]) of one polygon, the corners `face` of
/// `positions`, fanned from its first corner: the sample and its area.
pub fn face(
    positions: &[Point3<f64>],
    face: &[usize],
    spacing: f64,
    mut visit: impl FnMut(Point3<f64>, f64),
) {
    for k in 1..face.len().saturating_sub(1) {
        let corners = [
            positions[face[0]],
            positions[face[k]],
            positions[face[k + 1]],
        ];
        triangle(&corners, spacing, &mut visit);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn samples_tile_a_triangle_with_its_area() {
        let t = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(1.0, 0.0, 0.0),
            Point3::new(0.3, 0.8, 0.0),
        ];
        let (mut count, mut area, mut centre) = (0, 0.0, Vector3::zeros());
        // The longest edge is 1.063: 10 splits of at most 0.11 each.
        triangle(&t, 0.11, |q, a| {
            count += 1;
            area += a;
            centre += q.coords * a;
        });
        assert_eq!(count, 100);
        assert!((area - 0.4).abs() < 1e-12);
        // The samples' weighted mean is the triangle's centroid.
        assert!((centre / area - Vector3::new(1.3 / 3.0, 0.8 / 3.0, 0.0)).norm() < 1e-12);
    }

    #[test]
    fn a_quad_is_fanned_into_two_triangles() {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let positions = [p(0.0, 0.0), p(2.0, 0.0), p(2.0, 1.0), p(0.0, 1.0)];
        let (mut area, mut count) = (0.0, 0);
        face(&positions, &[0, 1, 2, 3], 10.0, |_, a| {
            area += a;
            count += 1;
        });
        assert_eq!(count, 2);
        assert!((area - 2.0).abs() < 1e-12);
    }
}
