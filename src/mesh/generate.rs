//! Quad meshes made in code: regular grids for tests and the built-in example shell.

use nalgebra::Point3;

use super::PolyMesh;

/// The height field `z = height(x, y)` over the square `[-half, half]^2`, in `n` x `n` cells
/// of two triangles each, the cells split along whichever of the square's diagonals runs
/// through them (alternating): a groin or cloister vault's creases, or a fold along a
/// diagonal, then lie on mesh edges, as in a designer's mesh of joined patches.
///
/// # Panics
/// If `n` is zero.
pub fn diagonal_grid(n: usize, half: f64, height: impl Fn(f64, f64) -> f64) -> PolyMesh {
    assert!(n > 0, "a grid needs at least one cell");
    let at = |i: usize| -half + 2.0 * half * i as f64 / n as f64;
    let mut positions = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (at(i), at(j));
            positions.push(Point3::new(x, y, height(x, y)));
        }
    }
    let id = |i: usize, j: usize| i * (n + 1) + j;
    let mut faces = Vec::with_capacity(2 * n * n);
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                faces.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                faces.extend([vec![a, b, d], vec![b, c, d]]);
            }
        }
    }
    PolyMesh::new(positions, faces).expect("a grid is a valid mesh")
}

/// A flat `nx` x `ny` grid of unit-spaced square quads in the xy plane.
///
/// Face `i + nx * j` is the square `[i, i+1] x [j, j+1]`; vertex `i + (nx + 1) * j` sits at
/// `(i, j, 0)`. Faces are counter-clockwise seen from +z.
///
/// # Panics
/// If `nx` or `ny` is zero.
pub fn grid(nx: usize, ny: usize) -> PolyMesh {
    assert!(
        nx > 0 && ny > 0,
        "a grid needs at least one face in each direction"
    );
    let xs: Vec<f64> = (0..=nx).map(|i| i as f64).collect();
    let ys: Vec<f64> = (0..=ny).map(|j| j as f64).collect();
    lattice(&xs, &ys, |_, _| 0.0)
}

/// The paper's benchmark shell (section 4.2, Figure 9): a square-plan shell of side `span`,
/// supported at its four corners, meshed with quads whose edges are about `edge` long.
///
/// The surface is the translational surface `z = g(x) + g(y)` with the parabolic arch
/// `g(s) = rise / 2 * (1 - (2 s / span)^2)`: corners at `z = 0`, edge arches rising to
/// `rise / 2`, the crown at `rise` (a quarter of the span). Translational surfaces have
/// planar parallelogram faces, and spacing the grid lines at equal arc length along `g`
/// makes every face edge the same length along each family.
///
/// # Panics
/// If `span` or `edge` is not positive and finite.
pub fn corner_supported_shell(span: f64, edge: f64) -> PolyMesh {
    assert!(
        span > 0.0 && edge > 0.0 && span.is_finite() && edge.is_finite(),
        "span and edge must be positive"
    );
    let rise = span / 4.0;
    let g = |s: f64| rise / 2.0 * (1.0 - (2.0 * s / span).powi(2));
    let stations = equal_arc_stations(span, edge, g);
    lattice(&stations, &stations, |x, y| g(x) + g(y))
}

/// Parameters `s` in `[-span/2, span/2]` splitting the arch `(s, g(s))` into pieces of equal
/// arc length, as many as make each piece closest to `edge`.
fn equal_arc_stations(span: f64, edge: f64, g: impl Fn(f64) -> f64) -> Vec<f64> {
    const SAMPLES: usize = 4096;
    let s_at = |k: usize| -span / 2.0 + span * k as f64 / SAMPLES as f64;
    let mut arc = vec![0.0; SAMPLES + 1];
    for k in 1..=SAMPLES {
        let (s0, s1) = (s_at(k - 1), s_at(k));
        arc[k] = arc[k - 1] + (s1 - s0).hypot(g(s1) - g(s0));
    }
    let total = arc[SAMPLES];
    let pieces = ((total / edge).round() as usize).max(1);
    (0..=pieces)
        .map(|i| {
            let target = total * i as f64 / pieces as f64;
            let k = arc.partition_point(|&a| a < target).clamp(1, SAMPLES);
            let t = (target - arc[k - 1]) / (arc[k] - arc[k - 1]);
            s_at(k - 1) + t * (s_at(k) - s_at(k - 1))
        })
        .collect()
}

/// Splits every quad along its diagonal 0-2 into two triangles (other faces are kept), e.g.
/// to feed a generated surface to the remesher as the triangle mesh a designer would export.
pub fn triangulate_quads(mesh: &PolyMesh) -> PolyMesh {
    let faces = mesh
        .faces()
        .iter()
        .flat_map(|f| match f[..] {
            [a, b, c, d] => vec![vec![a, b, c], vec![a, c, d]],
            _ => vec![f.clone()],
        })
        .collect();
    PolyMesh::new(mesh.positions().to_vec(), faces).expect("splitting quads keeps a mesh valid")
}

/// A quad lattice over the parameter lines `xs` x `ys` lifted by `z(x, y)`.
fn lattice(xs: &[f64], ys: &[f64], z: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let (nx, ny) = (xs.len() - 1, ys.len() - 1);
    let positions = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
        .map(|(x, y)| Point3::new(x, y, z(x, y)))
        .collect();
    let vertex = |i: usize, j: usize| i + (nx + 1) * j;
    let faces = (0..ny)
        .flat_map(|j| {
            (0..nx).map(move |i| {
                vec![
                    vertex(i, j),
                    vertex(i + 1, j),
                    vertex(i + 1, j + 1),
                    vertex(i, j + 1),
                ]
            })
        })
        .collect();
    PolyMesh::new(positions, faces).expect("a lattice is a valid mesh")
}

/// A closed cube of side `size` centred at the origin, each side an `n` x `n` grid of quads,
/// normals pointing out: the closed surface a designer may hand in by mistake.
///
/// # Panics
/// If `n` is zero or `size` not positive and finite.
pub fn closed_box(size: f64, n: usize) -> PolyMesh {
    assert!(
        n > 0 && size > 0.0 && size.is_finite(),
        "a box needs a size and faces"
    );
    let mut positions = Vec::new();
    let mut faces = Vec::new();
    for k in 0..3 {
        for sign in [-1.0, 1.0] {
            let axis = |i: usize| nalgebra::Vector3::ith((k + i) % 3, 1.0);
            // u x v points out of the box.
            let (u, v) = if sign > 0.0 {
                (axis(1), axis(2))
            } else {
                (axis(2), axis(1))
            };
            let centre = axis(0) * (sign * size / 2.0);
            let first = positions.len();
            for j in 0..=n {
                for i in 0..=n {
                    let (a, b) = (i as f64 / n as f64 - 0.5, j as f64 / n as f64 - 0.5);
                    positions.push(Point3::from(centre + u * (a * size) + v * (b * size)));
                }
            }
            let vertex = |i: usize, j: usize| first + i + (n + 1) * j;
            for j in 0..n {
                for i in 0..n {
                    faces.push(vec![
                        vertex(i, j),
                        vertex(i + 1, j),
                        vertex(i + 1, j + 1),
                        vertex(i, j + 1),
                    ]);
                }
            }
        }
    }
    // The sides share their edges: join their corners.
    let (positions, faces, _) = super::weld::weld(positions, faces, size * 1e-9);
    PolyMesh::new(positions, faces).expect("a welded box is a valid closed mesh")
}

/// A spherical cap of `radius` covering `area_fraction` of the sphere (0.6 reaches past the
/// equator, so its rim overhangs), triangulated with edges of about `edge`: rings of
/// vertices at equal steps of polar angle, each with as many vertices as its circumference
/// holds at that spacing, neighbouring rings zipped into near-equilateral triangles. The
/// crown is on +z, the rim lies in the plane z = 0 and faces are counter-clockwise seen from
/// outside (the test and benchmark dome of the remesher: every point of a sphere is umbilic).
///
/// # Panics
/// If `radius` or `edge` is not positive and finite, `edge` is not smaller than the radius,
/// or `area_fraction` is not in `(0, 1)`.
pub fn spherical_cap(radius: f64, area_fraction: f64, edge: f64) -> PolyMesh {
    assert!(
        radius.is_finite() && edge.is_finite() && radius > 0.0 && edge > 0.0 && edge < radius,
        "radius and edge must be positive, the edge smaller than the radius"
    );
    assert!(
        area_fraction > 0.0 && area_fraction < 1.0,
        "the cap covers a fraction of the sphere in (0, 1)"
    );
    // Cap area 2 pi R h = fraction * 4 pi R^2: height h = 2 R fraction.
    let theta_max = (1.0 - 2.0 * area_fraction).acos();
    let rings = ((radius * theta_max / edge).round() as usize).max(1);
    let z_rim = radius * theta_max.cos();
    let profile: Vec<(f64, f64)> = (0..=rings)
        .map(|k| {
            let theta = theta_max * k as f64 / rings as f64;
            (radius * theta.sin(), radius * theta.cos() - z_rim)
        })
        .collect();
    of_revolution(&profile, edge)
}

/// A cone of base `radius` and `height` (apex on +z, base rim in the plane z = 0),
/// triangulated with edges of about `edge` as [`spherical_cap`] is: developable, with its
/// curvature lines (the rulings and the rings) converging on the apex.
///
/// # Panics
/// If `radius`, `height` or `edge` is not positive and finite, or `edge` is not smaller than
/// the radius.
pub fn cone(radius: f64, height: f64, edge: f64) -> PolyMesh {
    assert!(
        [radius, height, edge]
            .iter()
            .all(|x| x.is_finite() && *x > 0.0)
            && edge < radius,
        "radius, height and edge must be positive, the edge smaller than the radius"
    );
    let rings = ((radius.hypot(height) / edge).round() as usize).max(1);
    let profile: Vec<(f64, f64)> = (0..=rings)
        .map(|k| {
            let s = k as f64 / rings as f64;
            (radius * s, height * (1.0 - s))
        })
        .collect();
    of_revolution(&profile, edge)
}

/// The surface of revolution about z through the `profile`'s (radius, z) points, the first
/// on the axis: a ring of vertices per point, each with as many vertices as its circumference
/// holds at `edge` (at least 6), neighbouring rings zipped into near-equilateral triangles,
/// counter-clockwise seen from outside.
fn of_revolution(profile: &[(f64, f64)], edge: f64) -> PolyMesh {
    use std::f64::consts::TAU;
    let (_, z_apex) = profile[0];
    let mut positions = vec![Point3::new(0.0, 0.0, z_apex)];
    // First vertex and vertex count of each ring; ring 0 is the apex.
    let mut ring = vec![(0usize, 1usize)];
    for &(r, z) in &profile[1..] {
        let count = ((TAU * r / edge).round() as usize).max(6);
        ring.push((positions.len(), count));
        for i in 0..count {
            let phi = TAU * i as f64 / count as f64;
            positions.push(Point3::new(r * phi.cos(), r * phi.sin(), z));
        }
    }
    let mut faces = Vec::new();
    for k in 1..ring.len() {
        let (inner, m) = ring[k - 1];
        let (outer, n) = ring[k];
        let at = |first: usize, count: usize, i: usize| first + i % count;
        if m == 1 {
            faces.extend((0..n).map(|j| vec![inner, at(outer, n, j), at(outer, n, j + 1)]));
            continue;
        }
        // Zip the two rings by azimuth: advance on whichever ring's next vertex comes first.
        let (mut i, mut j) = (0, 0);
        while i < m || j < n {
            let next_inner = (i + 1) as f64 / m as f64;
            let next_outer = (j + 1) as f64 / n as f64;
            if j < n && (i == m || next_outer <= next_inner) {
                faces.push(vec![at(inner, m, i), at(outer, n, j), at(outer, n, j + 1)]);
                j += 1;
            } else {
                faces.push(vec![at(inner, m, i), at(outer, n, j), at(inner, m, i + 1)]);
                i += 1;
            }
        }
    }
    PolyMesh::new(positions, faces).expect("a zipped surface of revolution is a valid mesh")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Topology;

    #[test]
    fn a_closed_box_is_closed_and_faces_out() {
        let cube = closed_box(2.0, 3);
        assert_eq!(cube.face_count(), 54);
        assert_eq!(cube.positions().len(), 6 * 9 + 2);
        let topology = Topology::new(&cube).unwrap();
        assert!(topology.edges().iter().all(|e| !e.is_boundary()));
        // Outward normals: each face's normal points away from the centre.
        for f in 0..cube.face_count() {
            assert!(cube.face_area_vector(f).dot(&cube.face_centroid(f).coords) > 0.0);
        }
    }

    #[test]
    fn spherical_cap_is_on_its_sphere_with_an_overhanging_rim_and_outward_faces() {
        let (radius, fraction, edge) = (3.0, 0.6, 0.2);
        let cap = spherical_cap(radius, fraction, edge);
        let theta_max = (1.0 - 2.0 * fraction).acos();
        let centre = Point3::new(0.0, 0.0, -radius * theta_max.cos());
        for p in cap.positions() {
            assert!(((p - centre).norm() - radius).abs() < 1e-9);
            assert!(p.z >= -1e-9, "the rim is the lowest level");
        }
        // Area close to the cap's 2 pi R h, h = 2 R fraction.
        let exact = 2.0 * std::f64::consts::PI * radius * 2.0 * radius * fraction;
        assert!((cap.area() - exact).abs() / exact < 0.01, "{}", cap.area());
        // Triangles near-equilateral: every edge within a factor of two of `edge`.
        for f in cap.faces() {
            assert_eq!(f.len(), 3);
            for k in 0..3 {
                let l = (cap.positions()[f[k]] - cap.positions()[f[(k + 1) % 3]]).norm();
                assert!(l > 0.5 * edge && l < 2.0 * edge, "edge {l}");
            }
            // Counter-clockwise seen from outside: the face normal points away from the centre.
            let [a, b, c] = [0, 1, 2].map(|k| cap.positions()[f[k]]);
            let n = (b - a).cross(&(c - a));
            assert!(n.dot(&(a - centre)) > 0.0);
        }
        // The rim overhangs: it lies below the equator, so the cap is wider above it.
        let rim = cap
            .positions()
            .iter()
            .filter(|p| p.z.abs() < 1e-9)
            .map(|p| p.x.hypot(p.y))
            .fold(0.0, f64::max);
        let widest = cap
            .positions()
            .iter()
            .map(|p| p.x.hypot(p.y))
            .fold(0.0, f64::max);
        assert!(widest > rim + 1e-3, "widest {widest} rim {rim}");
    }
}
