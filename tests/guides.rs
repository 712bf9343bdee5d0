//! Guide curves (issue 20): polylines the quad rows follow, checked on two surfaces whose own
//! field runs elsewhere: the paper's corner-supported shell (its crosses follow the edges and
//! the principal curvature, along x and y) with a guide drawn at 30 degrees across it, and an
//! umbilic dome with a guide down a meridian. Bad guide input is refused with the curve at
//! fault.

use nalgebra::Vector3;
use tilepattern::mesh::{PolyMesh, generate};
use tilepattern::remesh::{
    BoundaryAlignment, GuideCurves, RemeshError, RemeshOptions, UserField, remesh,
};

const T: f64 = 0.145;
/// How far a guide pulls, in target edges (documented on `GuideCurves`).
const REACH: f64 = 2.0;
const SPAN: f64 = 3.0;

/// The shell of the paper's Figure 9 as a designer exports it: triangles of a third of `T`.
fn shell() -> PolyMesh {
    generate::triangulate_quads(&generate::corner_supported_shell(SPAN, T / 3.0))
}

/// Height of the shell: `g(x) + g(y)` with the parabolic arch `g` of rise `SPAN / 8`.
fn shell_height(x: f64, y: f64) -> f64 {
    let g = |s: f64| SPAN / 8.0 * (1.0 - (2.0 * s / SPAN).powi(2));
    g(x) + g(y)
}

fn shell_normal(p: &Vector3<f64>) -> Vector3<f64> {
    let dg = |s: f64| -SPAN / 8.0 * 8.0 * s / (SPAN * SPAN);
    Vector3::new(-dg(p.x), -dg(p.y), 1.0).normalize()
}

/// A guide on the shell along the plan line through its centre at `degrees` from x, one
/// point every 5 cm, from edge to edge.
fn shell_guide(degrees: f64) -> Vec<[f64; 3]> {
    let (c, s) = (degrees.to_radians().cos(), degrees.to_radians().sin());
    let half = SPAN / 2.0 / c.abs().max(s.abs()) - 1e-9;
    let n = (2.0 * half / 0.05).ceil() as usize;
    (0..=n)
        .map(|k| {
            let r = -half + 2.0 * half * k as f64 / n as f64;
            let (x, y) = (r * c, r * s);
            [x, y, shell_height(x, y)]
        })
        .collect()
}

const RADIUS: f64 = 3.0;
const FRACTION: f64 = 0.3;

fn dome() -> PolyMesh {
    generate::spherical_cap(RADIUS, FRACTION, 0.1)
}

fn dome_centre() -> Vector3<f64> {
    Vector3::new(0.0, 0.0, -RADIUS * (1.0 - 2.0 * FRACTION))
}

/// A guide down the dome's meridian at `degrees` from x, from the crown to the rim.
fn meridian_guide(degrees: f64) -> Vec<[f64; 3]> {
    let theta_max = (1.0 - 2.0 * FRACTION).acos();
    let (c, s) = (degrees.to_radians().cos(), degrees.to_radians().sin());
    let n = 60;
    (0..=n)
        .map(|k| {
            let theta = theta_max * k as f64 / n as f64;
            let p = dome_centre()
                + RADIUS * Vector3::new(theta.sin() * c, theta.sin() * s, theta.cos());
            [p.x, p.y, p.z]
        })
        .collect()
}

/// Of the quad edges whose midpoint is within `within` of the guide polyline: how many, and
/// the share within `tolerance` degrees of the tangent of the guide's closest segment or its
/// perpendicular, measured in the tangent plane (`normal`).
fn along_guide(
    quads: &PolyMesh,
    guide: &[[f64; 3]],
    normal: impl Fn(&Vector3<f64>) -> Vector3<f64>,
    within: f64,
    tolerance: f64,
) -> (usize, f64) {
    let mut edges = std::collections::BTreeSet::new();
    for face in quads.faces() {
        for k in 0..face.len() {
            let (a, b) = (face[k], face[(k + 1) % face.len()]);
            edges.insert((a.min(b), a.max(b)));
        }
    }
    let g: Vec<Vector3<f64>> = guide.iter().map(|p| Vector3::from(*p)).collect();
    let p = quads.positions();
    let (mut near, mut good) = (0usize, 0usize);
    for (a, b) in edges {
        let mid = (p[a].coords + p[b].coords) * 0.5;
        let (distance, tangent) = g
            .windows(2)
            .map(|w| {
                let d = w[1] - w[0];
                let t = ((mid - w[0]).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
                ((w[0] + d * t - mid).norm(), d)
            })
            .min_by(|x, y| x.0.total_cmp(&y.0))
            .unwrap();
        if distance > within {
            continue;
        }
        near += 1;
        let n = normal(&mid);
        let e = p[b].coords - p[a].coords;
        let e = e - n * n.dot(&e);
        let t = tangent - n * n.dot(&tangent);
        let angle = (e.dot(&t).abs() / (e.norm() * t.norm()))
            .min(1.0)
            .acos()
            .to_degrees();
        if angle.min(90.0 - angle) <= tolerance {
            good += 1;
        }
    }
    (near, good as f64 / near.max(1) as f64)
}

fn options(guides: Option<GuideCurves>) -> RemeshOptions {
    let mut o = RemeshOptions::default();
    o.target_edge = T;
    o.guides = guides;
    o
}

#[test]
fn quads_follow_a_guide_drawn_across_the_shell() {
    let shell = shell();
    let guide = shell_guide(30.0);
    let free = remesh(&shell, &options(None)).unwrap();
    let guides = GuideCurves::new(vec![guide.clone()]);
    let guided = remesh(&shell, &options(Some(guides.clone()))).unwrap();
    for within in [1.0, REACH] {
        let (n0, before) = along_guide(&free.quads, &guide, shell_normal, within * T, 10.0);
        let (n1, after) = along_guide(&guided.quads, &guide, shell_normal, within * T, 10.0);
        eprintln!(
            "shell, edges within {within} t of a 30 degree guide: {before:.3} of {n0} within 10 degrees without, {after:.3} of {n1} with it"
        );
        // The shell's own crosses run along x and y, 30 degrees off the guide's: no edge
        // follows the guide by chance.
        assert!(before < 0.1, "{before:.3} along the guide without it");
        assert!(
            after >= 0.9,
            "{after:.3} of {n1} edges within {within} t along the guide"
        );
        assert!(n1 > 60, "{n1} edges near the guide");
    }
    // Deterministic, byte for byte.
    let again = remesh(&shell, &options(Some(guides))).unwrap();
    assert_eq!(again.quads.positions(), guided.quads.positions());
    assert_eq!(again.quads.faces(), guided.quads.faces());
}

#[test]
fn quads_follow_a_guide_down_a_meridian_of_the_dome() {
    let dome = dome();
    let guide = meridian_guide(30.0);
    let normal = |p: &Vector3<f64>| (p - dome_centre()).normalize();
    let free = remesh(&dome, &options(None)).unwrap();
    let guided = remesh(&dome, &options(Some(GuideCurves::new(vec![guide.clone()])))).unwrap();
    let (n0, before) = along_guide(&free.quads, &guide, normal, REACH * T, 10.0);
    let (n1, after) = along_guide(&guided.quads, &guide, normal, REACH * T, 10.0);
    eprintln!(
        "dome, edges within 2 t of a meridian guide: {before:.3} of {n0} within 10 degrees without, {after:.3} of {n1} with it"
    );
    assert!(before < 0.5, "{before:.3} along the meridian by chance");
    assert!(after >= 0.85, "{after:.3} of {n1} edges along the meridian");
}

#[test]
fn guides_and_a_designer_field_combine() {
    // A field along x over the whole shell at a fifth of the share, and a guide at 30
    // degrees: near the guide the guide leads, far from it the field; with guide weight 0
    // the guide is ignored.
    let shell = shell();
    let guide = shell_guide(30.0);
    let along_x = vec![[1.0, 0.0, 0.0]; shell.positions().len()];
    let field = UserField::for_mesh(&shell, along_x, 0.2).unwrap();
    let with_field = |guides: Option<GuideCurves>| {
        let mut o = options(guides);
        o.user_field = Some(field.clone());
        o
    };
    let quads = remesh(
        &shell,
        &with_field(Some(GuideCurves::new(vec![guide.clone()]))),
    )
    .unwrap()
    .quads;
    let (_, near) = along_guide(&quads, &guide, shell_normal, T, 10.0);
    let x_axis = [[-SPAN, 0.0, 0.0], [SPAN, 0.0, 0.0]];
    let (_, x) = along_guide(&quads, &x_axis, shell_normal, 10.0 * SPAN, 10.0);
    let alone = remesh(&shell, &with_field(None)).unwrap().quads;
    let (_, near_alone) = along_guide(&alone, &guide, shell_normal, T, 10.0);
    let (_, x_alone) = along_guide(&alone, &x_axis, shell_normal, 10.0 * SPAN, 10.0);
    eprintln!(
        "shell with a field along x (share 0.2): edges within t of the guide along it {near_alone:.3} without the guide, {near:.3} with it; edges along x overall {x_alone:.3} and {x:.3}"
    );
    assert!(near >= 0.5, "{near:.3} along the guide with a field");
    assert!(
        near_alone < 0.1,
        "{near_alone:.3} along the guide without it"
    );
    assert!(x >= 0.5, "{x:.3} of the edges still follow the field");
    let ignored = with_field(Some(GuideCurves {
        weight: 0.0,
        ..GuideCurves::new(vec![guide.clone()])
    }));
    assert_eq!(ignored.effective_boundary(), BoundaryAlignment::Never);
    let quads = remesh(&shell, &ignored).unwrap().quads;
    assert_eq!(
        quads.faces(),
        alone.faces(),
        "guide weight 0 changes nothing"
    );
}

#[test]
fn bad_guides_name_the_curve_at_fault() {
    let shell = shell();
    let good = shell_guide(30.0);
    let run = |curves: Vec<Vec<[f64; 3]>>| {
        remesh(&shell, &options(Some(GuideCurves::new(curves)))).unwrap_err()
    };
    assert_eq!(
        run(vec![good.clone(), vec![[0.0, 0.0, 0.75]]]),
        RemeshError::GuideTooShort {
            curve: 1,
            points: 1
        }
    );
    let mut bad = good.clone();
    bad[4][2] = f64::NAN;
    let err = run(vec![good.clone(), good.clone(), bad]);
    assert!(
        matches!(
            err,
            RemeshError::BadGuidePoint {
                curve: 2,
                point: 4,
                ..
            }
        ),
        "{err}"
    );
    assert_eq!(
        run(vec![vec![[0.0, 0.0, 0.75]; 4]]),
        RemeshError::GuideZeroLength { curve: 0 }
    );
    // The guide drawn in plan at z = 2 m (over a shell 0.75 m high), or in millimetres.
    let lifted: Vec<[f64; 3]> = good.iter().map(|p| [p[0], p[1], 2.0]).collect();
    let err = run(vec![good.clone(), lifted]);
    assert!(
        matches!(err, RemeshError::GuideOffSurface { curve: 1, distance, .. } if distance > 1.0),
        "{err}"
    );
    assert!(err.to_string().contains("guide curve 1"), "{err}");
    let millimetres: Vec<[f64; 3]> = good
        .iter()
        .map(|p| [p[0] * 1000.0, p[1] * 1000.0, p[2] * 1000.0])
        .collect();
    assert!(matches!(
        run(vec![millimetres]),
        RemeshError::GuideOffSurface { curve: 0, .. }
    ));
    let weight = {
        let mut o = options(None);
        o.guides = Some(GuideCurves {
            weight: f64::NAN,
            ..GuideCurves::new(vec![good])
        });
        o
    };
    assert!(matches!(
        remesh(&shell, &weight),
        Err(RemeshError::BadGuideWeight(_))
    ));
}
