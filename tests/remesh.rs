//! Stage 1 acceptance on small surfaces generated in code: a hypar patch, a spherical cap, a
//! barrel vault and a square with a round hole. Each must come out as a pure, valid quad mesh
//! covering the input, on it, with edges near the target; runs are byte-identical; bad
//! options are refused with the right error.

use std::f64::consts::PI;

use std::time::Duration;

use nalgebra::{Point3, Vector3};
use tilepattern::control::Control;
use tilepattern::mesh::{PolyMesh, generate, obj};
use tilepattern::remesh::{
    BoundaryAlignment, FieldDirection, Metrics, RemeshError, RemeshOptions, metrics, remesh,
    remesh_with,
};

/// Triangulates a regular (u, v) grid of `nu x nv` cells mapped through `f`, alternating the
/// diagonal so the mesh has no preferred direction.
fn grid_surface(
    nu: usize,
    nv: usize,
    closed_u: bool,
    f: impl Fn(f64, f64) -> [f64; 3],
) -> PolyMesh {
    grid_surface_split(nu, nv, closed_u, true, f)
}

/// [`grid_surface`], splitting every cell along the same diagonal unless `alternate` (as a
/// CAD export of a revolved surface's quads does).
fn grid_surface_split(
    nu: usize,
    nv: usize,
    closed_u: bool,
    alternate: bool,
    f: impl Fn(f64, f64) -> [f64; 3],
) -> PolyMesh {
    let cols = if closed_u { nu } else { nu + 1 };
    let mut positions = Vec::new();
    for j in 0..=nv {
        for i in 0..cols {
            let p = f(i as f64 / nu as f64, j as f64 / nv as f64);
            positions.push(Point3::new(p[0], p[1], p[2]));
        }
    }
    let id = |i: usize, j: usize| j * cols + (i % cols);
    let mut faces = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if !alternate || (i + j) % 2 == 0 {
                faces.push(vec![a, b, c]);
                faces.push(vec![a, c, d]);
            } else {
                faces.push(vec![a, b, d]);
                faces.push(vec![b, c, d]);
            }
        }
    }
    PolyMesh::new(positions, faces).expect("generated surface is valid")
}

/// Hyperbolic paraboloid z = 0.25 x y over a 3 x 3 square.
fn hypar() -> PolyMesh {
    grid_surface(36, 36, false, |u, v| {
        let (x, y) = (3.0 * u - 1.5, 3.0 * v - 1.5);
        [x, y, 0.25 * x * y]
    })
}

/// Spherical cap of radius 3 and half-angle 40 degrees: a square grid squeezed onto the
/// disk (elliptical grid mapping), then lifted onto the sphere.
fn cap() -> PolyMesh {
    let radius = 3.0;
    let rim = radius * 40f64.to_radians().sin();
    grid_surface(40, 40, false, |u, v| {
        let (x, y) = (2.0 * u - 1.0, 2.0 * v - 1.0);
        let (dx, dy) = (
            x * (1.0 - y * y / 2.0).sqrt(),
            y * (1.0 - x * x / 2.0).sqrt(),
        );
        let (px, py) = (dx * rim, dy * rim);
        [px, py, (radius * radius - px * px - py * py).sqrt()]
    })
}

/// Half cylinder (barrel vault) of radius 1.2 and length 3.
fn vault() -> PolyMesh {
    grid_surface(30, 40, false, |u, v| {
        let a = PI * u;
        [1.2 * a.cos(), 3.0 * v, 1.2 * a.sin()]
    })
}

/// A barrel vault of span 1.6 bent through a quarter turn around a centre 2 away: its
/// outer edge is 1.8 times as long as its inner edge, so quads of one size need rows that end
/// inside the surface (the tubemesh's bend, in small).
fn bent_vault() -> PolyMesh {
    grid_surface(48, 24, false, |u, v| {
        let (around, across) = (0.5 * PI * u, PI * v);
        let r = 2.0 + 0.8 * (1.0 - across.cos());
        [r * around.cos(), r * around.sin(), 0.8 * across.sin()]
    })
}

/// 3 x 3 square with a round hole of radius 0.6, meshed between the circle and the square.
fn holed() -> PolyMesh {
    grid_surface(96, 18, true, |u, v| {
        let a = 2.0 * PI * u;
        let (c, s) = (a.cos(), a.sin());
        let inner = [0.6 * c, 0.6 * s];
        let reach = 1.5 / c.abs().max(s.abs());
        let outer = [reach * c, reach * s];
        [
            inner[0] + (outer[0] - inner[0]) * v,
            inner[1] + (outer[1] - inner[1]) * v,
            0.0,
        ]
    })
}

/// Hypar z = 0.3 x y over a convex quadrilateral with a 21 degree corner (a tongue of the
/// shell narrower than a quad for its last quad lengths).
fn acute_hypar() -> PolyMesh {
    let corners = [[0.0, 0.0], [3.0, 0.0], [3.2, 1.6], [0.9, 0.35]];
    grid_surface(48, 24, false, |u, v| {
        let lerp =
            |a: [f64; 2], b: [f64; 2], s: f64| [a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s];
        let bottom = lerp(corners[0], corners[1], u);
        let top = lerp(corners[3], corners[2], u);
        let [x, y] = lerp(bottom, top, v);
        [x, y, 0.3 * (x - 1.5) * (y - 0.8)]
    })
}

/// A gently curved 3 x 2 patch whose bottom edge carries a comb of five needle triangles
/// (teeth half a quad wide at the base and four quads long, in narrow notches), as left by
/// subdividing a mesh with slivers at a support.
fn comb_patch() -> PolyMesh {
    let (nu, nv) = (36, 24);
    let base = grid_surface(nu, nv, false, |u, v| {
        let (x, y) = (3.0 * u, 2.0 * v);
        [x, y, 0.03 * (x - 1.5) * (x - 1.5) + 0.1 * y]
    });
    let mut positions = base.positions().to_vec();
    let mut faces = base.faces().to_vec();
    for i in 1..6 {
        let (a, b) = (positions[i], positions[i + 1]);
        let lift = if i % 2 == 0 { 0.12 } else { -0.12 };
        positions.push(Point3::new(
            0.5 * (a.x + b.x) - 0.3 + 0.12 * (i - 1) as f64,
            -0.6,
            a.z + lift,
        ));
        // The boundary edge i -> i+1 has the patch on its left; the tooth goes on its right.
        faces.push(vec![i + 1, i, positions.len() - 1]);
    }
    PolyMesh::new(positions, faces).expect("comb patch is valid")
}

/// A flat 3 x 2.5 patch whose bottom-left corner (1.2 x 0.45) is folded up by 90 degrees
/// along a sharp crease: quads laid flat across the crease would leave the surface, as they
/// did at the crumpled supports of the benchmark shells.
fn folded_corner() -> PolyMesh {
    grid_surface(36, 30, false, |u, v| {
        let (x, y) = (3.0 * u, 2.5 * v);
        if y < 0.45 && x < 1.2 {
            [x, 0.45, 0.45 - y]
        } else {
            [x, y, 0.0]
        }
    })
}

/// True when every vertex's faces form one fan (a manifold surface, boundary included).
fn vertex_manifold(mesh: &PolyMesh) -> bool {
    let n = mesh.positions().len();
    let mut around: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
    for f in mesh.faces() {
        for i in 0..f.len() {
            let (prev, next) = (f[(i + f.len() - 1) % f.len()], f[(i + 1) % f.len()]);
            around[f[i]].push((prev, next));
        }
    }
    around.iter().all(|corners| {
        if corners.is_empty() {
            return true;
        }
        // Walk the fan from one corner through shared edges; it must reach every corner.
        let mut seen = vec![false; corners.len()];
        let mut stack = vec![0];
        seen[0] = true;
        while let Some(c) = stack.pop() {
            for (k, other) in corners.iter().enumerate() {
                let (p, q) = corners[c];
                if !seen[k] && (other.0 == q || other.1 == p || other.0 == p || other.1 == q) {
                    seen[k] = true;
                    stack.push(k);
                }
            }
        }
        seen.iter().all(|&s| s)
    })
}

fn options(t: f64) -> RemeshOptions {
    let mut o = RemeshOptions::default();
    o.target_edge = t;
    o
}

/// The thresholds every generated surface must meet at its target edge.
fn check(name: &str, m: &Metrics, max_irregular: usize) {
    println!("{name}: {m:?}");
    assert!(m.pure_quad, "{name}: not pure quad");
    assert!(m.faces > 50, "{name}: only {} faces", m.faces);
    assert!(
        m.interior_irregular_vertices <= max_irregular,
        "{name}: {} irregular vertices",
        m.interior_irregular_vertices
    );
    assert_eq!(
        m.boundary_vertices_off_input, 0,
        "{name}: boundary vertices off the input boundary"
    );
    assert!(
        (m.mean_edge_ratio - 1.0).abs() <= 0.08,
        "{name}: mean edge ratio {}",
        m.mean_edge_ratio
    );
    assert!(
        m.edges_within_20pct >= 0.8,
        "{name}: edges within 20%: {}",
        m.edges_within_20pct
    );
    assert!(
        m.faces_area_within_20pct >= 0.7,
        "{name}: areas within 20%: {}",
        m.faces_area_within_20pct
    );
    assert!(
        m.p95_corner_angle_deviation_deg <= 20.0,
        "{name}: p95 angle deviation {}",
        m.p95_corner_angle_deviation_deg
    );
    assert!(
        m.max_distance_to_input_ratio <= 0.1,
        "{name}: max distance {}",
        m.max_distance_to_input_ratio
    );
    assert!(
        m.area_covered_ratio >= 0.98,
        "{name}: area covered {}",
        m.area_covered_ratio
    );
}

#[test]
fn hypar_patch_becomes_regular_quads() {
    let input = hypar();
    let result = remesh(&input, &options(0.15)).expect("remesh");
    check("hypar", &result.metrics, 4);
    // The public metrics function agrees with what remesh reported.
    let again = metrics(&input, &result.quads, 0.15);
    assert_eq!(again.faces, result.metrics.faces);
    assert_eq!(
        again.interior_irregular_vertices,
        result.metrics.interior_irregular_vertices
    );
}

/// Hyperbolic paraboloid z = 0.24 (x - 2.5)(y - 2.5) over a 5 x 5 square with `n x n` quads
/// split along one diagonal, as a coarse render mesh has them (issue 19's real inputs).
fn hypar_5m(n: usize) -> PolyMesh {
    let at = |i: usize, j: usize| j * (n + 1) + i;
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (5.0 * i as f64 / n as f64, 5.0 * j as f64 / n as f64);
            positions.push(Point3::new(x, y, 0.24 * (x - 2.5) * (y - 2.5)));
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            faces.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    PolyMesh::new(positions, faces).expect("generated surface is valid")
}

#[test]
fn a_coarse_input_is_remeshed_as_its_fine_twin() {
    // Faces of four quads (625 mm) against faces of half a quad: the field is solved at the
    // lattice's resolution from the coarse vertices' curvature, so the coarse mesh comes
    // close to the fine one's clean grid (0 irregular vertices, 98 % of edges within 20 %).
    // Solved on the 81 coarse vertices alone, the field gave 4 irregular vertices and 96 %
    // here, 10 in the middle of the same shell under `tilepattern run` (level courses),
    // where tiles then left a p95 joint deviation of 6.5 mm against 1.4 on the fine twin.
    let fine = remesh(&hypar_5m(64), &options(0.145)).expect("remesh fine");
    let coarse = remesh(&hypar_5m(8), &options(0.145)).expect("remesh coarse");
    check("fine hypar", &fine.metrics, 0);
    check("coarse hypar", &coarse.metrics, 2);
    assert!(
        coarse.metrics.edges_within_20pct >= fine.metrics.edges_within_20pct - 0.01,
        "{} of edges within 20 %",
        coarse.metrics.edges_within_20pct
    );
}

#[test]
fn spherical_cap_is_covered() {
    let result = remesh(&cap(), &options(0.15)).expect("remesh");
    check("cap", &result.metrics, 16);
}

/// Issue 19's 3 m dome: a spherical cap of radius 3 over 60 % of the sphere (its rim
/// overhangs), about 18k near-equilateral triangles; every point of it is umbilic.
fn dome_3m() -> PolyMesh {
    generate::spherical_cap(3.0, 0.6, 0.087)
}

#[test]
fn a_3m_dome_is_remeshed_soundly() {
    // At the default pipeline's 150 mm quads (3128 of them): a sound pure quad mesh on the
    // surface, with 15 interior irregular vertices today (31 before cone clusters were
    // collapsed and staircase teeth closed by one quad; issue 19 asks for 12 or fewer, see
    // `issue_19_dome_acceptance`) and 92 % of edges within 20 %.
    let result = remesh(&dome_3m(), &options(0.15)).expect("remesh");
    let m = &result.metrics;
    check("3 m dome", m, 20);
    assert!(m.edges_within_20pct >= 0.9, "{m:?}");
}

#[test]
#[ignore = "issue 19's acceptance, not met yet: 15 interior irregular vertices (at most 12), 92 % of edges within 20 % (at least 95 %)"]
fn issue_19_dome_acceptance() {
    let result = remesh(&dome_3m(), &options(0.15)).expect("remesh");
    let m = &result.metrics;
    assert!(m.interior_irregular_vertices <= 12, "{m:?}");
    assert!(m.edges_within_20pct >= 0.95, "{m:?}");
}

/// A hemisphere of radius 3 as a modeller facets it, in 96 x 24 latitude-longitude rows
/// (flat facets of about 196 mm), then triangulated evenly at about 90 mm without those
/// rows (as an STL export or an isotropic remesh gives it): the rings of an even cap
/// projected from the centre onto the facets. Its triangles bend only at the facets' creases.
fn faceted_hemisphere() -> PolyMesh {
    use std::f64::consts::{FRAC_PI_2, TAU};
    let (radius, rows, sectors) = (3.0, 24, 96);
    let corner = |j: usize, i: usize| {
        let (theta, phi) = (
            FRAC_PI_2 * j as f64 / rows as f64,
            TAU * (i % sectors) as f64 / sectors as f64,
        );
        Vector3::new(
            theta.sin() * phi.cos(),
            theta.sin() * phi.sin(),
            theta.cos(),
        ) * radius
    };
    let even = generate::spherical_cap(radius, 0.5, 0.09);
    let positions = even
        .positions()
        .iter()
        .map(|p| {
            let d = p.coords.normalize();
            let theta = d.z.clamp(-1.0, 1.0).acos();
            let phi = d.y.atan2(d.x).rem_euclid(TAU);
            let j = ((theta / FRAC_PI_2 * rows as f64) as usize).min(rows - 1);
            let i = (phi / TAU * sectors as f64) as usize;
            let [a, b, c] = if j == 0 {
                [corner(0, 0), corner(1, i), corner(1, i + 1)]
            } else {
                [corner(j, i), corner(j, i + 1), corner(j + 1, i)]
            };
            let n = (b - a).cross(&(c - a));
            Point3::from(d * (n.dot(&a) / n.dot(&d)))
        })
        .collect();
    PolyMesh::new(positions, even.faces().to_vec()).expect("generated surface is valid")
}

#[test]
fn a_faceted_dome_is_not_mistaken_for_a_ribbed_one() {
    // Read over the triangles' 2-ring, the facets' creases gave many of this dome's vertices
    // principal directions along the rows, and the quads ran in rings along the rim, too
    // short across the rows and too long along them (measured: mean edge 1.12 t, 44 % of
    // edges and 18 % of quad areas within 20 %). Read over three quad edges the dome is
    // umbilic, as the hemisphere it models (8 irregular vertices, mean edge 1.02 t, 86 % and
    // 70 %).
    let result = remesh(&faceted_hemisphere(), &options(0.15)).expect("remesh");
    let m = &result.metrics;
    println!("faceted hemisphere: {m:?}");
    assert!(m.pure_quad && m.boundary_vertices_off_input == 0, "{m:?}");
    assert!(m.interior_irregular_vertices <= 16, "{m:?}");
    assert!((m.mean_edge_ratio - 1.0).abs() <= 0.05, "{m:?}");
    assert!(m.edges_within_20pct >= 0.8, "{m:?}");
    assert!(m.faces_area_within_20pct >= 0.6, "{m:?}");
}

#[test]
fn a_bend_gets_rows_that_end_inside_rather_than_stretched_quads() {
    // Cancelling every lattice dislocation gives no irregular vertex here but stretched and
    // squeezed quads (measured: 73 % of edges and 46 % of areas within 20 %); keeping the
    // far-apart ones as row ends (34 irregular vertices) gives 90 % and 81 %.
    let result = remesh(&bent_vault(), &options(0.12)).expect("remesh");
    let m = &result.metrics;
    check("bent vault", m, 40);
    assert!(
        m.edges_within_20pct >= 0.85,
        "edges within 20%: {}",
        m.edges_within_20pct
    );
    assert!(
        m.faces_area_within_20pct >= 0.75,
        "areas within 20%: {}",
        m.faces_area_within_20pct
    );
    assert!(
        m.p95_corner_angle_deviation_deg <= 15.0,
        "p95 angle deviation {}",
        m.p95_corner_angle_deviation_deg
    );
}

/// A dome of revolution on a drum, meshed as a revolved surface (every cell split along the
/// same diagonal): the zone of a sphere of radius 2 from 20 degrees off its axis (an
/// oculus) down to its equator, on a vertical drum 0.3 high. The drum's curvature
/// sets the crosses along the rings everywhere, so the rows along them must end all over the
/// dome: 2.9 times as many at the equator as at the oculus.
fn dome_on_drum() -> PolyMesh {
    let zone = 70f64.to_radians();
    let (radius, drum) = (2.0, 0.3);
    let length = radius * zone + drum;
    grid_surface_split(96, 40, true, false, |u, v| {
        let along = v * length;
        let (r, z) = if along <= radius * zone {
            let polar = 20f64.to_radians() + along / radius;
            (radius * polar.sin(), radius * polar.cos())
        } else {
            (radius, -(along - radius * zone))
        };
        let a = 2.0 * PI * u;
        [r * a.cos(), r * a.sin(), z]
    })
}

#[test]
fn a_dome_on_a_drum_gets_rows_that_end_rather_than_stretched_quads() {
    // Read edge by edge on the working surface, the first lattice ended almost no rows here
    // and stretched them instead (quads of 1.38 target edges on average, 24 % of edges
    // within 20 %, 96 % of the surface covered; 81.5 %, 100 % from the coarse start).
    let result = remesh(&dome_on_drum(), &options(0.15)).expect("remesh");
    let m = &result.metrics;
    println!("dome on a drum: {m:?}");
    assert!(m.pure_quad);
    assert!((m.mean_edge_ratio - 1.0).abs() <= 0.1, "{m:?}");
    assert!(m.area_covered_ratio >= 0.98, "{m:?}");
    assert!(m.edges_within_20pct >= 0.7, "{m:?}");
    assert!(m.coarse_start, "{m:?}");
    // A spherical cap's rows end where its field's cones are, not all over it.
    assert!(
        !remesh(&cap(), &options(0.15))
            .expect("remesh")
            .metrics
            .coarse_start
    );
}

/// A pillow vault (10 x 7, rise 2.5) triangulated without rows: a 70 x 70 grid whose inner
/// vertices are jittered by up to 0.35 of a cell and whose cells are split along a random
/// diagonal, as an STL export, a scan or a remesher gives.
fn jittered_pillow_vault() -> PolyMesh {
    let n = 70;
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut unit = move || {
        // xorshift64*: a fixed sequence in [0, 1).
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        (state.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (mut u, mut v) = (i as f64 / n as f64, j as f64 / n as f64);
            if 0 < i && i < n && 0 < j && j < n {
                u += (unit() - 0.5) * 0.7 / n as f64;
                v += (unit() - 0.5) * 0.7 / n as f64;
            }
            let z = 2.5 * (PI * u).sin() * (PI * v).sin();
            positions.push(Point3::new(10.0 * u, 7.0 * v, z));
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if unit() < 0.5 {
                faces.extend([vec![a, b, c], vec![a, c, d]]);
            } else {
                faces.extend([vec![a, b, d], vec![b, c, d]]);
            }
        }
    }
    PolyMesh::new(positions, faces).expect("generated surface is valid")
}

#[test]
fn a_triangulation_without_rows_keeps_few_row_ends() {
    // The first lattice of an unstructured triangulation holds dislocations the shape does
    // not need. Integrated at the surface's conformal scale it holds fewer, in pairs that
    // cancel, and those left in calm patches leave through the boundary before it is pinned
    // (measured: 23 irregular vertices, 97 % of edges within 20 %; 55 and 96 % integrated at
    // one spacing; 76 and 95 % when none leave either). The same vault in rows gets 4.
    let result = remesh(&jittered_pillow_vault(), &options(0.145)).expect("remesh");
    check("jittered pillow vault", &result.metrics, 35);
}

#[test]
fn barrel_vault_follows_curvature() {
    let result = remesh(&vault(), &options(0.15)).expect("remesh");
    check("vault", &result.metrics, 4);
}

#[test]
fn hole_keeps_its_boundary() {
    let result = remesh(&holed(), &options(0.15)).expect("remesh");
    check("holed", &result.metrics, 12);
}

#[test]
fn other_field_directions_still_give_pure_quads() {
    let input = vault();
    for direction in [
        FieldDirection::Vector([0.0, 1.0, 0.0]),
        FieldDirection::Angle(45.0),
    ] {
        let o = {
            let mut o = RemeshOptions::default();
            o.target_edge = 0.15;
            o.direction = direction;
            o
        };
        let result = remesh(&input, &o).expect("remesh");
        let m = &result.metrics;
        println!("{direction:?}: {m:?}");
        assert!(m.pure_quad);
        assert!(m.max_distance_to_input_ratio <= 0.1);
        assert!(m.area_covered_ratio >= 0.95);
    }
}

#[test]
fn every_boundary_mode_gives_a_sound_mesh() {
    // Always: rows follow the round rim too, which costs cones and dislocations but must
    // stay a clean cover; Never: quads are trimmed at the square's edges.
    for boundary in [BoundaryAlignment::Always, BoundaryAlignment::Never] {
        let o = {
            let mut o = RemeshOptions::default();
            o.target_edge = 0.15;
            o.boundary = boundary;
            o
        };
        let result = remesh(&cap(), &o).expect("remesh");
        let m = &result.metrics;
        println!("{boundary:?}: {m:?}");
        assert!(m.pure_quad);
        assert_eq!(m.boundary_vertices_off_input, 0);
        assert!(
            (m.mean_edge_ratio - 1.0).abs() <= 0.2,
            "{boundary:?}: mean edge {}",
            m.mean_edge_ratio
        );
        assert!(
            m.max_distance_to_input_ratio <= 0.1,
            "{boundary:?}: distance {}",
            m.max_distance_to_input_ratio
        );
        assert!(
            m.area_covered_ratio >= 0.98,
            "{boundary:?}: covered {}",
            m.area_covered_ratio
        );
    }
}

/// The acceptance lines that concern the surface and its boundary, not the quads' shape.
fn check_fit(name: &str, mesh: &PolyMesh, m: &Metrics, max_irregular: usize, min_covered: f64) {
    println!("{name}: {m:?}");
    assert!(m.pure_quad, "{name}: not pure quad");
    assert!(vertex_manifold(mesh), "{name}: a vertex is pinched");
    assert_eq!(
        m.boundary_vertices_off_input, 0,
        "{name}: boundary vertices off the input boundary"
    );
    assert!(
        m.max_distance_to_input_ratio <= 0.1,
        "{name}: max distance {}",
        m.max_distance_to_input_ratio
    );
    assert!(
        m.area_covered_ratio >= min_covered,
        "{name}: area covered {}",
        m.area_covered_ratio
    );
    assert!(
        m.interior_irregular_vertices <= max_irregular,
        "{name}: {} irregular vertices",
        m.interior_irregular_vertices
    );
    assert!(
        (m.mean_edge_ratio - 1.0).abs() <= 0.08,
        "{name}: mean edge ratio {}",
        m.mean_edge_ratio
    );
}

#[test]
fn acute_corner_stays_on_the_surface() {
    // Rows cannot follow both sides of a 21 degree tongue; the quads there are sheared, but
    // they must stay on the surface, cover it and keep the rest of the patch regular.
    let input = acute_hypar();
    let result = remesh(&input, &options(0.15)).expect("remesh");
    check_fit("acute hypar", &result.quads, &result.metrics, 6, 0.99);
    assert!(
        result.metrics.edges_within_20pct >= 0.55,
        "acute hypar: edges within 20%: {}",
        result.metrics.edges_within_20pct
    );
}

#[test]
fn needle_teeth_are_not_bridged() {
    let input = comb_patch();
    let result = remesh(&input, &options(0.15)).expect("remesh");
    // The teeth themselves (2 % of the area) are narrower than a quad.
    check_fit("comb", &result.quads, &result.metrics, 4, 0.975);
    assert!(
        result.metrics.edges_within_20pct >= 0.9,
        "comb: edges within 20%: {}",
        result.metrics.edges_within_20pct
    );
    assert!(
        result.metrics.faces_area_within_20pct >= 0.85,
        "comb: areas within 20%: {}",
        result.metrics.faces_area_within_20pct
    );
}

#[test]
fn folded_corner_is_followed_not_spanned() {
    let input = folded_corner();
    let result = remesh(&input, &options(0.15)).expect("remesh");
    check_fit("folded corner", &result.quads, &result.metrics, 8, 0.99);
    assert!(
        result.metrics.edges_within_20pct >= 0.85,
        "folded: edges within 20%: {}",
        result.metrics.edges_within_20pct
    );
}

#[test]
fn a_hole_leaves_every_vertex_manifold() {
    let result = remesh(&holed(), &options(0.15)).expect("remesh");
    assert!(vertex_manifold(&result.quads));
    assert!(
        result.quads.faces().iter().enumerate().all(|(f, _)| result
            .quads
            .face_area_vector(f)
            .norm()
            > 1e-6)
    );
}

#[test]
fn progress_is_reported_and_cancel_stops_the_stage() {
    let input = hypar();
    let mut seen: Vec<f64> = Vec::new();
    let mut record = |fraction: f64| {
        seen.push(fraction);
        true
    };
    let result = remesh_with(
        &input,
        &options(0.15),
        &mut Control::with_progress(&mut record),
    );
    assert!(result.is_ok());
    assert!(seen.len() >= 5, "{seen:?}");
    assert_eq!(seen.first(), Some(&0.0));
    assert_eq!(seen.last(), Some(&1.0));
    assert!(
        seen.windows(2).all(|w| w[0] <= w[1]),
        "progress went backwards: {seen:?}"
    );
    assert!(seen.iter().any(|&f| f > 0.0 && f < 1.0));

    // Cancelled in every part of the stage: an error, and no callback after the cancel.
    for stop_at in [0.01, 0.1, 0.3, 0.8] {
        let mut calls_after = 0;
        let mut stopped = false;
        let mut cancel = |fraction: f64| {
            if stopped {
                calls_after += 1;
            }
            stopped = fraction >= stop_at;
            !stopped
        };
        let error = remesh_with(
            &input,
            &options(0.15),
            &mut Control::with_progress(&mut cancel),
        )
        .err();
        assert_eq!(error, Some(RemeshError::Cancelled), "stop at {stop_at}");
        assert_eq!(calls_after, 0);
    }
}

#[test]
fn time_limit_without_a_mesh_is_an_error() {
    let input = hypar();
    let none = {
        let mut o = options(0.15);
        o.time_limit = Duration::ZERO;
        o
    };
    assert!(matches!(
        remesh(&input, &none),
        Err(RemeshError::TimeLimit { .. })
    ));
    // A generous limit changes nothing.
    let generous = {
        let mut o = options(0.15);
        o.time_limit = Duration::from_secs(600);
        o
    };
    let (a, b) = (
        remesh(&input, &generous).expect("remesh"),
        remesh(&input, &options(0.15)).expect("remesh"),
    );
    assert_eq!(obj::to_string(&a.quads), obj::to_string(&b.quads));
    assert!(matches!(
        RemeshOptions::time_limit_from_secs(-1.0),
        Err(RemeshError::BadTimeLimit(_))
    ));
    assert!(matches!(
        RemeshOptions::time_limit_from_secs(f64::NAN),
        Err(RemeshError::BadTimeLimit(_))
    ));
}

#[test]
fn pinched_input_is_refused() {
    // Two triangles meeting at one vertex: the surface is not a manifold there.
    let positions = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
    ]
    .map(|p| Point3::new(p[0], p[1], p[2]))
    .to_vec();
    let input =
        PolyMesh::new(positions, vec![vec![0, 1, 2], vec![0, 3, 4]]).expect("valid polygon soup");
    let error = remesh(&input, &options(0.1)).err();
    assert!(
        matches!(error, Some(RemeshError::UnsupportedInput(_))),
        "{error:?}"
    );
}

#[test]
fn shapeup_stays_on_the_surface() {
    let input = cap();
    let o = {
        let mut o = RemeshOptions::default();
        o.target_edge = 0.15;
        o.shapeup = true;
        o
    };
    let result = remesh(&input, &o).expect("remesh");
    check("cap+shapeup", &result.metrics, 16);
}

#[test]
fn runs_are_byte_identical() {
    // The folded corner goes through every fitting step (row extension, peeling, strip
    // splitting), the hole through the hole filling.
    for input in [holed(), folded_corner()] {
        let a = remesh(&input, &options(0.15)).expect("remesh");
        let b = remesh(&input, &options(0.15)).expect("remesh");
        assert_eq!(obj::to_string(&a.quads), obj::to_string(&b.quads));
    }
}

#[test]
fn bad_options_are_refused() {
    let input = hypar();
    for t in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(
            matches!(
                remesh(&input, &options(t)),
                Err(RemeshError::BadTargetEdge(_))
            ),
            "t = {t}"
        );
    }
    assert!(matches!(
        remesh(&input, &options(100.0)),
        Err(RemeshError::TargetEdgeTooLarge { .. })
    ));
    assert!(matches!(
        remesh(&input, &options(1e-5)),
        Err(RemeshError::TargetEdgeTooSmall { .. })
    ));
    let zero = {
        let mut o = options(0.15);
        o.direction = FieldDirection::Vector([0.0; 3]);
        o
    };
    assert!(matches!(
        remesh(&input, &zero),
        Err(RemeshError::BadDirection(_))
    ));
    let nan = {
        let mut o = options(0.15);
        o.direction = FieldDirection::Angle(f64::NAN);
        o
    };
    assert!(matches!(
        remesh(&input, &nan),
        Err(RemeshError::BadAngle(_))
    ));
    let tolerance = {
        let mut o = options(0.15);
        o.shapeup = true;
        o.shapeup_tolerance = -1.0;
        o
    };
    assert!(matches!(
        remesh(&input, &tolerance),
        Err(RemeshError::BadShapeupTolerance(_))
    ));
    // Messages name the problem.
    let message = remesh(&input, &options(-1.0))
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(message.contains("-1"), "{message}");
}
