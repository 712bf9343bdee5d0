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
    if l2 <= 0.0 { 0.0 } else { ((p - a).dot(&d) / l2).clamp(0.0, 1.0) }
}

/// Closest point on triangle `abc` to `p` (Ericson, *Real-Time Collision Detection*, 5.1.5).
pub fn on_triangle(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> Vector3<f64> {
    let w = triangle_weights(p, a, b, c);
    a * w[0] + b * w[1] + c * w[2]
}

/// Barycentric weights (summing to 1, each in `[0, 1]`) of the point of triangle `abc`
/// closest to `p`: by the Voronoi regions of its corners, edges and face.
pub fn triangle_weights(p: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>, c: &Vector3<f64>) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return [1.0 - v, v, 0.0];
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return [1.0 - w, 0.0, w];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - w, w];
    }
    let denom = va + vb + vc;
    if denom.abs() < 1e-300 {
        // A degenerate triangle: the nearest of its edges.
        let edges = [(0, 1, a, b), (1, 2, b, c), (2, 0, c, a)];
        let (i, j, t) = edges
            .iter()
            .map(|&(i, j, x, y)| (i, j, segment_parameter(p, x, y)))
            .min_by(|&(i, j, t), &(k, l, s)| {
                let at = |i: usize, j: usize, t: f64| [a, b, c][i] * (1.0 - t) + [a, b, c][j] * t;
                (at(i, j, t) - p).norm_squared().total_cmp(&(at(k, l, s) - p).norm_squared())
            })
            .expect("three edges");
        let mut w = [0.0; 3];
        w[i] += 1.0 - t;
        w[j] += t;
        return w;
    }
    let (v, w) = (vb / denom, vc / denom);
    [1.0 - v - w, v, w]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segment_ends_and_middle() {
        let (a, b) = (Vector3::new(0.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 0.0));
        assert_eq!(on_segment(&Vector3::new(-1.0, 1.0, 0.0), &a, &b), a);
        assert_eq!(on_segment(&Vector3::new(3.0, 1.0, 0.0), &a, &b), b);
        assert_eq!(on_segment(&Vector3::new(0.5, 1.0, 7.0), &a, &b), Vector3::new(0.5, 0.0, 0.0));
        assert_eq!(on_segment(&Vector3::new(0.5, 1.0, 7.0), &a, &a), a);
    }

    #[test]
    fn triangle_agrees_with_dense_sampling() {
        let (a, b, c) = (Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 0.2, 0.1), Vector3::new(0.3, 0.9, -0.2));
        let mut s = 1u64;
        let mut rnd = move || {
            s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 3.0 - 1.0
        };
        for _ in 0..300 {
            let p = Vector3::new(rnd(), rnd(), rnd());
            let q = on_triangle(&p, &a, &b, &c);
            let w = triangle_weights(&p, &a, &b, &c);
            assert!(w.iter().all(|&x| (-1e-12..=1.0 + 1e-12).contains(&x)) && (w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
            let mut best = f64::INFINITY;
            let n = 120;
            for i in 0..=n {
                for j in 0..=n - i {
                    let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                    best = best.min((a + (b - a) * u + (c - a) * v - p).norm());
                }
            }
            assert!((q - p).norm() <= best + 1e-12, "closest point is no closer than a sample");
            assert!((q - p).norm() >= best - 0.02, "closest point within the sampling's resolution");
        }
    }

    #[test]
    fn degenerate_triangle_falls_back_to_its_edges() {
        let (a, b, c) = (Vector3::zeros(), Vector3::new(1.0, 0.0, 0.0), Vector3::new(2.0, 0.0, 0.0));
        let q = on_triangle(&Vector3::new(1.5, 1.0, 0.0), &a, &b, &c);
        assert!((q - Vector3::new(1.5, 0.0, 0.0)).norm() < 1e-12);
    }
}
