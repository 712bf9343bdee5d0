//! Points and polygons in a plane: areas, clipping to convex windows, and the separation of
//! convex polygons by separating axes.

/// A point in a plane.
pub type Point2 = [f64; 2];

/// `a - b`.
pub fn sub(a: Point2, b: Point2) -> Point2 {
    [a[0] - b[0], a[1] - b[1]]
}

/// The z component of `a × b`: positive when `b` turns counter-clockwise from `a`.
pub fn cross(a: Point2, b: Point2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// `a · b`.
pub fn dot(a: Point2, b: Point2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// Distance between two points.
pub fn dist(a: Point2, b: Point2) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The point `a + t (b - a)`.
pub fn lerp(a: Point2, b: Point2, t: f64) -> Point2 {
    [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]
}

/// Shoelace area, positive for counter-clockwise loops.
pub fn signed_area(points: &[Point2]) -> f64 {
    (0..points.len())
        .map(|i| cross(points[i], points[(i + 1) % points.len()]))
        .sum::<f64>()
        / 2.0
}

/// Distance from `q` to segment `ab`, and which end is closest when it is an end (0 or 1).
pub fn point_segment(q: Point2, a: Point2, b: Point2) -> (f64, Option<usize>) {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        dot(sub(q, a), ab) / len2
    } else {
        0.0
    };
    let (t, end) = if t <= 0.0 {
        (0.0, Some(0))
    } else if t >= 1.0 {
        (1.0, Some(1))
    } else {
        (t, None)
    };
    (dist(q, lerp(a, b, t)), end)
}

/// The part of `polygon` on the left of the directed line through `a` and `b`
/// (Sutherland-Hodgman, one edge): empty when nothing is left.
pub fn clip_left_of(polygon: &[Point2], a: Point2, b: Point2) -> Vec<Point2> {
    let side = |p: Point2| cross(sub(b, a), sub(p, a));
    let mut out = Vec::with_capacity(polygon.len() + 2);
    for k in 0..polygon.len() {
        let (p, q) = (polygon[k], polygon[(k + 1) % polygon.len()]);
        let (sp, sq) = (side(p), side(q));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sq >= 0.0) {
            out.push(lerp(p, q, sp / (sp - sq)));
        }
    }
    out
}

/// The part of `polygon` inside the convex, counter-clockwise `window`.
pub fn clip_to_convex(polygon: &[Point2], window: &[Point2]) -> Vec<Point2> {
    let mut poly = polygon.to_vec();
    for i in 0..window.len() {
        if poly.is_empty() {
            break;
        }
        poly = clip_left_of(&poly, window[i], window[(i + 1) % window.len()]);
    }
    poly
}

/// Winding number of `loops` around `q` (holes, clockwise, count against their outer loop).
pub fn winding(loops: &[Vec<Point2>], q: Point2) -> i32 {
    let mut w = 0;
    for l in loops {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            let side = cross(sub(b, a), sub(q, a));
            if a[1] <= q[1] && b[1] > q[1] && side > 0.0 {
                w += 1;
            } else if a[1] > q[1] && b[1] <= q[1] && side < 0.0 {
                w -= 1;
            }
        }
    }
    w
}

/// Signed separation of two convex, counter-clockwise polygons by separating axes, and the
/// unit axis it was found along (pointing from `p` towards `q`).
///
/// Every edge normal of either polygon is a candidate axis; along it the separation is the
/// gap between the two projections. The largest is returned: positive, the polygons are
/// that far apart along it (their distance when the nearest features are a corner and an
/// edge, a lower bound on it otherwise); zero or negative, they overlap, and its magnitude is
/// how far one must move along the axis to clear the other (the penetration depth).
pub fn separation(p: &[Point2], q: &[Point2]) -> (f64, Point2) {
    let mut best = (f64::NEG_INFINITY, [1.0, 0.0]);
    for (from, to, sign) in [(p, q, 1.0), (q, p, -1.0)] {
        for i in 0..from.len() {
            let e = sub(from[(i + 1) % from.len()], from[i]);
            let len = e[0].hypot(e[1]);
            if len <= 0.0 {
                continue;
            }
            // Outward normal of a counter-clockwise polygon's edge.
            let n = [e[1] / len, -e[0] / len];
            let reach = from
                .iter()
                .map(|&v| dot(n, v))
                .fold(f64::NEG_INFINITY, f64::max);
            let start = to.iter().map(|&v| dot(n, v)).fold(f64::INFINITY, f64::min);
            let gap = start - reach;
            if gap > best.0 {
                best = (gap, [sign * n[0], sign * n[1]]);
            }
        }
    }
    best
}

/// Convex hull of `points`, counter-clockwise, without collinear points (Andrew's monotone
/// chain).
pub fn convex_hull(points: &[Point2]) -> Vec<Point2> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut hull: Vec<Point2> = Vec::with_capacity(2 * pts.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point2>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(
                    sub(hull[hull.len() - 1], hull[hull.len() - 2]),
                    sub(p, hull[hull.len() - 2]),
                ) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect(cx: f64, cy: f64, hx: f64, hy: f64) -> Vec<Point2> {
        vec![
            [cx - hx, cy - hy],
            [cx + hx, cy - hy],
            [cx + hx, cy + hy],
            [cx - hx, cy + hy],
        ]
    }

    #[test]
    fn separation_of_rectangles_side_by_side_and_overlapping() {
        let a = rect(0.0, 0.0, 1.0, 0.5);
        let (gap, axis) = separation(&a, &rect(2.3, 0.2, 1.0, 0.5));
        assert!((gap - 0.3).abs() < 1e-12 && (axis[0] - 1.0).abs() < 1e-12);
        let (gap, axis) = separation(&a, &rect(0.4, -1.05, 1.0, 0.5));
        assert!((gap - 0.05).abs() < 1e-12 && (axis[1] + 1.0).abs() < 1e-12);
        let (gap, _) = separation(&a, &rect(1.8, 0.0, 1.0, 0.5));
        assert!((gap + 0.2).abs() < 1e-12, "overlap of 0.2 along x");
    }

    #[test]
    fn separation_of_a_turned_rectangle_is_its_nearest_corner() {
        let a = rect(0.0, 0.0, 1.0, 1.0);
        // A square turned 45 degrees whose corner points at a's right side, 0.1 away.
        let h = std::f64::consts::SQRT_2;
        let b = vec![
            [1.1, 0.0],
            [1.1 + h, -h],
            [1.1 + 2.0 * h, 0.0],
            [1.1 + h, h],
        ];
        let b: Vec<Point2> = b.into_iter().rev().collect::<Vec<_>>();
        let b = if signed_area(&b) < 0.0 {
            b.into_iter().rev().collect()
        } else {
            b
        };
        assert!((separation(&a, &b).0 - 0.1).abs() < 1e-12);
    }

    #[test]
    fn clipping_keeps_the_area_inside() {
        let square = rect(0.0, 0.0, 1.0, 1.0);
        let half = clip_left_of(&square, [0.0, -5.0], [0.0, 5.0]);
        assert!((signed_area(&half) - 2.0).abs() < 1e-12);
        let window = rect(0.5, 0.5, 1.0, 1.0);
        assert!((signed_area(&clip_to_convex(&square, &window)) - 2.25).abs() < 1e-12);
        assert!(clip_to_convex(&square, &rect(5.0, 5.0, 1.0, 1.0)).is_empty());
    }

    #[test]
    fn hull_winding_and_segment_distance() {
        let pts = [
            [0.0, 0.0],
            [2.0, 0.0],
            [1.0, 0.5],
            [2.0, 2.0],
            [0.0, 2.0],
            [1.0, 2.0],
        ];
        let hull = convex_hull(&pts);
        assert_eq!(hull.len(), 4);
        assert!((signed_area(&hull) - 4.0).abs() < 1e-12);
        assert_eq!(winding(std::slice::from_ref(&hull), [1.0, 1.0]), 1);
        assert_eq!(winding(&[hull], [3.0, 1.0]), 0);
        assert_eq!(
            point_segment([0.5, 1.0], [0.0, 0.0], [1.0, 0.0]),
            (1.0, None)
        );
        assert_eq!(
            point_segment([-1.0, 0.0], [0.0, 0.0], [1.0, 0.0]),
            (1.0, Some(0))
        );
    }
}
