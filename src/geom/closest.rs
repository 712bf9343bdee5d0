//! Closest points on segments and triangles.

use nalgebra::Vector3;

/// Closest point on segment `ab` to `p`.
pub fn on_segment(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    a + (b - a) * segment_parameter(p, a, b)
}

/// Parameter `t` in `[0, 1]` of the point of segment `ab` closest to `p` (`a + t (b - a)`);
/// 0 for a segment of zero length.
pub fn segment_parameter(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    if l2 <= 0.0 {
        0.0
    } else {
        ((p - a).dot(&d) / l2).clamp(0.0, 1.0)
    }
}

/// Closest point on triangle `abc` to `p` (Ericson, *Real-Time Collision Detection*, 5.1.5).
pub fn on_triangle(
    p: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> Vector3<f64> {
    match feature(p, a, b, c) {
        Feature::Corner(k) => *[a, b, c][k],
        Feature::Ab(v) => a + (b - a) * v,
        Feature::Ac(w) => a + (c - a) * w,
        Feature::Bc(w) => b + (c - b) * w,
        Feature::Face(v, w) => a + (b - a) * v + (c - a) * w,
        Feature::Degenerate => nearest_edge(p, a, b, c).3,
    }
}

/// Barycentric weights (summing to 1, each in `[0, 1]`) of the point of triangle `abc`
/// closest to `p`: by the Voronoi regions of its corners, edges and face.
pub fn triangle_weights(
    p: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> [f64; 3] {
    match feature(p, a, b, c) {
        Feature::Corner(k) => {
            let mut w = [0.0; 3];
            w[k] = 1.0;
            w
        }
        Feature::Ab(v) => [1.0 - v, v, 0.0],
        Feature::Ac(w) => [1.0 - w, 0.0, w],
        Feature::Bc(w) => [0.0, 1.0 - w, w],
        Feature::Face(v, w) => [1.0 - v - w, v, w],
        Feature::Degenerate => {
            let (i, j, t, _) = nearest_edge(p, a, b, c);
            let mut w = [0.0; 3];
            w[i] += 1.0 - t;
            w[j] += t;
            w
        }
    }
}

/// The feature of a triangle `abc` nearest to a point, with the parameters of the point on it.
enum Feature {
    /// Corner 0 (`a`), 1 (`b`) or 2 (`c`).
    Corner(usize),
    /// `a + v (b - a)`.
    Ab(f64),
    /// `a + w (c - a)`.
    Ac(f64),
    /// `b + w (c - b)`.
    Bc(f64),
    /// `a + v (b - a) + w (c - a)`, inside the face.
    Face(f64, f64),
    /// The triangle has no area: the nearest of its edges.
    Degenerate,
}

/// Which Voronoi region of triangle `abc` holds `p` (Ericson 5.1.5).
fn feature(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> Feature {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return Feature::Corner(0);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return Feature::Corner(1);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return Feature::Ab(d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return Feature::Corner(2);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return Feature::Ac(d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return Feature::Bc((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom.abs() < 1e-300 {
        return Feature::Degenerate;
    }
    Feature::Face(vb / denom, vc / denom)
}

/// The edge of triangle `abc` nearest to `p` (the first of `ab`, `bc`, `ca` on a tie), as
/// (corner, corner, parameter along the edge, closest point).
fn nearest_edge(
    p: &Vector3<f64>,
    a: &Vector3<f64>,
    b: &Vector3<f64>,
    c: &Vector3<f64>,
) -> (usize, usize, f64, Vector3<f64>) {
    [(0, 1, a, b), (1, 2, b, c), (2, 0, c, a)]
        .map(|(i, j, x, y)| {
            let t = segment_parameter(p, x, y);
            (i, j, t, x + (y - x) * t)
        })
        .into_iter()
        .min_by(|x, y| {
            (x.3 - p)
                .norm_squared()
                .total_cmp(&(y.3 - p).norm_squared())
        })
        .expect("three edges")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_ends_and_middle() {
        let (a, b) = (Vector3::new(0.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 0.0));
        assert_eq!(on_segment(&Vector3::new(-1.0, 1.0, 0.0), &a, &b), a);
        assert_eq!(on_segment(&Vector3::new(3.0, 1.0, 0.0), &a, &b), b);
        assert_eq!(
            on_segment(&Vector3::new(0.5, 1.0, 7.0), &a, &b),
            Vector3::new(0.5, 0.0, 0.0)
        );
        assert_eq!(on_segment(&Vector3::new(0.5, 1.0, 7.0), &a, &a), a);
    }

    #[test]
    fn triangle_agrees_with_dense_sampling() {
        let (a, b, c) = (
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.2, 0.1),
            Vector3::new(0.3, 0.9, -0.2),
        );
        let mut s = 1u64;
        let mut rnd = move || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 3.0 - 1.0
        };
        for _ in 0..300 {
            let p = Vector3::new(rnd(), rnd(), rnd());
            let q = on_triangle(&p, &a, &b, &c);
            let w = triangle_weights(&p, &a, &b, &c);
            assert!(
                w.iter().all(|&x| (-1e-12..=1.0 + 1e-12).contains(&x))
                    && (w.iter().sum::<f64>() - 1.0).abs() < 1e-12
            );
            let mut best = f64::INFINITY;
            let n = 120;
            for i in 0..=n {
                for j in 0..=n - i {
                    let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                    best = best.min((a + (b - a) * u + (c - a) * v - p).norm());
                }
            }
            assert!(
                (q - p).norm() <= best + 1e-12,
                "closest point is no closer than a sample"
            );
            assert!(
                (q - p).norm() >= best - 0.02,
                "closest point within the sampling's resolution"
            );
        }
    }

    #[test]
    fn point_and_weights_name_the_same_point() {
        // A flat triangle, queried from every Voronoi region (corners, edges, face) and off
        // its plane; and a degenerate one, whose nearest edge both must choose alike.
        let flat = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(0.2, 0.8, 0.0),
        ];
        let needle = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(1.0, 1.0, 0.0),
            Vector3::new(3.0, 3.0, 0.0),
        ];
        for [a, b, c] in [flat, needle] {
            for i in -4..=8 {
                for j in -4..=8 {
                    let p = Vector3::new(i as f64 * 0.25, j as f64 * 0.25, 0.3 * (i - j) as f64);
                    let q = on_triangle(&p, &a, &b, &c);
                    let w = triangle_weights(&p, &a, &b, &c);
                    assert!(
                        (a * w[0] + b * w[1] + c * w[2] - q).norm() < 1e-12,
                        "{p:?}: {q:?} vs {w:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn degenerate_triangle_falls_back_to_its_edges() {
        let (a, b, c) = (
            Vector3::zeros(),
            Vector3::new(1.0, 0.0, 0.0),
            Vector3::new(2.0, 0.0, 0.0),
        );
        let q = on_triangle(&Vector3::new(1.5, 1.0, 0.0), &a, &b, &c);
        assert!((q - Vector3::new(1.5, 0.0, 0.0)).norm() < 1e-12);
    }
}
