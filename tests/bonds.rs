//! Issue 20: the herringbone and the basket weave as bonds of the matching. On regular grids
//! their proven optimum is the textbook pattern, checked cell by cell; on the shared shells
//! they give valid matchings with an honest bound.

mod common;

use std::time::Duration;

use tilepattern::mesh::{Topology, generate};
use tilepattern::pattern::{self, Bond, DualGraph, Pattern, PatternOptions, SolveStatus};

type Cell = (i64, i64);

/// The eight symmetries of the square grid, as integer matrices (their inverse is their
/// transpose).
const SYMMETRIES: [[[i64; 2]; 2]; 8] = [
    [[1, 0], [0, 1]],
    [[0, -1], [1, 0]],
    [[-1, 0], [0, -1]],
    [[0, 1], [-1, 0]],
    [[-1, 0], [0, 1]],
    [[1, 0], [0, -1]],
    [[0, 1], [1, 0]],
    [[0, -1], [-1, 0]],
];

fn apply(m: [[i64; 2]; 2], c: Cell) -> Cell {
    (m[0][0] * c.0 + m[0][1] * c.1, m[1][0] * c.0 + m[1][1] * c.1)
}

fn transpose(m: [[i64; 2]; 2]) -> [[i64; 2]; 2] {
    [[m[0][0], m[1][0]], [m[0][1], m[1][1]]]
}

/// The textbook herringbone: the staircase of 2:1 tiles along the diagonals, each tile's
/// ends against the sides of perpendicular tiles, the two turned opposite ways. Returns the
/// cell that shares a tile with `c`.
fn herringbone(c: Cell) -> Cell {
    match (c.0 - c.1).rem_euclid(4) {
        0 => (c.0 + 1, c.1),
        1 => (c.0 - 1, c.1),
        2 => (c.0, c.1 - 1),
        _ => (c.0, c.1 + 1),
    }
}

/// The textbook basket weave: 2 x 2 squares of two parallel tiles, their direction
/// alternating like a checkerboard.
fn basket_weave(c: Cell) -> Cell {
    let (bx, by) = (c.0.div_euclid(2), c.1.div_euclid(2));
    if (bx + by).rem_euclid(2) == 0 {
        (c.0 ^ 1, c.1)
    } else {
        (c.0, c.1 ^ 1)
    }
}

/// The partner of each cell of a grid `n` cells wide in `found` (`None`: a half tile).
fn partners(n: usize, found: &Pattern) -> Vec<Option<Cell>> {
    let cell = |f: usize| ((f % n) as i64, (f / n) as i64);
    let mut partner = vec![None; found.faces];
    for &[a, b] in &found.pairs {
        partner[a] = Some(cell(b));
        partner[b] = Some(cell(a));
    }
    partner
}

/// True when some symmetry and shift of `textbook` pairs every cell at least `margin` from
/// the border of the `n` x `n` grid as `found` does.
fn matches_textbook(n: usize, found: &Pattern, textbook: fn(Cell) -> Cell, margin: i64) -> bool {
    let inside: Vec<Cell> = (margin..n as i64 - margin)
        .flat_map(|y| (margin..n as i64 - margin).map(move |x| (x, y)))
        .collect();
    matches_textbook_at(n, found, textbook, &inside)
}

/// True when some symmetry and shift of `textbook` pairs every one of `cells` of a grid `n`
/// cells wide as `found` does.
fn matches_textbook_at(
    n: usize,
    found: &Pattern,
    textbook: fn(Cell) -> Cell,
    cells: &[Cell],
) -> bool {
    let partner = partners(n, found);
    let n = n as i64;
    SYMMETRIES.iter().any(|&m| {
        (0..4).any(|sx| {
            (0..4).any(|sy| {
                let expected = |c: Cell| {
                    let u = apply(transpose(m), (c.0 - sx, c.1 - sy));
                    let p = apply(m, textbook(u));
                    (p.0 + sx, p.1 + sy)
                };
                cells
                    .iter()
                    .all(|&(x, y)| partner[(x + n * y) as usize] == Some(expected((x, y))))
            })
        })
    })
}

fn solve_grid(n: usize, bond: Bond) -> Pattern {
    let mesh = generate::grid(n, n);
    let options = {
        let mut o = PatternOptions::default();
        o.bond = bond;
        o.time_limit = Duration::from_secs(600);
        o
    };
    let found = pattern::solve(&mesh, &options).unwrap();
    assert!(common::is_valid_matching(&mesh, &found.pairs));
    found
}

/// Draws the pattern of an `n` x `n` grid (see [`picture_wide`]).
fn picture(n: usize, found: &Pattern) -> String {
    picture_wide(n, n, found)
}

#[test]
fn basket_weave_is_the_textbook_pattern_on_grids() {
    for n in [10, 12] {
        let found = solve_grid(n, Bond::BasketWeave { weight: 0.5 });
        let drawn = picture(n, &found);
        assert_eq!(found.status, SolveStatus::Optimal, "{n} x {n}\n{drawn}");
        assert_eq!(found.pairs.len(), n * n / 2, "{n} x {n}\n{drawn}");
        // Every cell, the border included.
        assert!(
            matches_textbook(n, &found, basket_weave, 0),
            "{n} x {n}\n{drawn}"
        );
        assert!(!matches_textbook(n, &found, herringbone, 2));
    }
}

#[test]
fn herringbone_is_the_textbook_pattern_on_grids() {
    for n in [10, 12] {
        let found = solve_grid(n, Bond::Herringbone { weight: 0.5 });
        let drawn = picture(n, &found);
        assert_eq!(found.status, SolveStatus::Optimal, "{n} x {n}\n{drawn}");
        // The zig-zag meets a square border at 45 degrees: along the border the optimum
        // trades tiles for joints, two cells deep. Every cell inside that is the textbook's.
        assert!(
            matches_textbook(n, &found, herringbone, 2),
            "{n} x {n}\n{drawn}"
        );
        assert!(!matches_textbook(n, &found, basket_weave, 2));
    }
}

#[test]
fn a_herringbone_band_inside_a_staggered_field_is_laid_as_asked() {
    // A 16 x 8 grid, staggered, with a band of herringbone 10 cells wide down its middle
    // (columns 3 to 12), as a herringbone soffit runs along a staggered vault.
    let (nx, ny) = (16usize, 8usize);
    let mesh = generate::grid(nx, ny);
    let staggered = Bond::Staggered { weight: 0.5 };
    let herring = Bond::Herringbone { weight: 1.0 };
    let in_band = |f: usize| (3..13).contains(&(f % nx));
    let zones: Vec<Bond> = (0..mesh.face_count())
        .map(|f| if in_band(f) { herring } else { staggered })
        .collect();
    let solve = |zones: Option<Vec<Bond>>| {
        let options = {
            let mut o = PatternOptions::default();
            o.bond = staggered;
            o.zones = zones;
            o.time_limit = Duration::from_secs(120);
            o
        };
        let found = pattern::solve(&mesh, &options).unwrap();
        assert!(common::is_valid_matching(&mesh, &found.pairs));
        found
    };
    let found = solve(Some(zones));
    let drawn = picture_wide(nx, ny, &found);
    eprintln!(
        "zones: objective {}, bound {}, {:?}, {:.1} s\n{drawn}",
        found.objective, found.bound, found.status, found.seconds
    );
    // Inside the band, two cells from its border: the textbook herringbone, cell by cell.
    let band: Vec<Cell> = (2..ny as i64 - 2)
        .flat_map(|y| (5..11).map(move |x| (x, y)))
        .collect();
    assert!(
        matches_textbook_at(nx, &found, herringbone, &band),
        "{}\n{drawn}",
        found.objective
    );
    // In the staggered fields, each 3 cells wide: a stagger, tile by tile, its continuous
    // joints (if any) only where the herringbone's border makes them the lesser cost.
    let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
    let field = |t: [usize; 2]| t.iter().all(|&f| !in_band(f));
    let joints_in_field = |p: &Pattern| {
        graph
            .continuous_joints()
            .iter()
            .filter(|&&[a, b]| {
                let (ta, tb) = (graph.tiles()[a].faces, graph.tiles()[b].faces);
                field(ta) && field(tb) && p.pairs.contains(&ta) && p.pairs.contains(&tb)
            })
            .count()
    };
    let joints = joints_in_field(&found);
    eprintln!("continuous joints in the staggered fields: {joints}");
    assert!(joints <= 2, "{joints}\n{drawn}");
    // Its objective is the zones' score, and at least the bound is honest.
    assert!(found.bound >= found.objective - 1e-9);
    // Without the zones the same cells are not herringbone: the zones lay it.
    let plain = solve(None);
    assert!(
        !matches_textbook_at(nx, &plain, herringbone, &band),
        "{}",
        picture_wide(nx, ny, &plain)
    );
}

/// Draws the pattern of an `nx` x `ny` grid: `-` a cell of a tile along x, `|` along y, `.`
/// a half tile.
fn picture_wide(nx: usize, ny: usize, found: &Pattern) -> String {
    let partner = partners(nx, found);
    let mut rows = Vec::new();
    for y in (0..ny).rev() {
        rows.push(
            (0..nx)
                .map(|x| match partner[x + nx * y] {
                    None => '.',
                    Some((_, py)) if py == y as i64 => '-',
                    Some(_) => '|',
                })
                .collect::<String>(),
        );
    }
    rows.join("\n")
}

/// On a grid, by geometry alone: `(end to end, one course apart)` for two disjoint tiles.
fn grid_relation(nx: usize, a: [usize; 2], b: [usize; 2]) -> (bool, bool) {
    let cell = |f: usize| ((f % nx) as i64, (f / nx) as i64);
    let along_x = |t: [usize; 2]| cell(t[0]).1 == cell(t[1]).1;
    if along_x(a) != along_x(b) {
        return (false, false);
    }
    // (along, across) coordinates of the tiles' direction; start: the smaller along.
    let key = |f: usize| {
        let c = cell(f);
        if along_x(a) { c } else { (c.1, c.0) }
    };
    let start = |t: [usize; 2]| (key(t[0]).0.min(key(t[1]).0), key(t[0]).1);
    let (sa, sb) = (start(a), start(b));
    (
        sa.1 == sb.1 && (sa.0 - sb.0).abs() == 2,
        sa.0 == sb.0 && (sa.1 - sb.1).abs() == 2,
    )
}

#[test]
fn end_to_end_and_one_course_apart_match_a_geometric_brute_force_on_grids() {
    for (nx, ny) in [(4, 5), (6, 3), (5, 5), (7, 6)] {
        let mesh = generate::grid(nx, ny);
        let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
        let (mut ends, mut apart) = (Vec::new(), Vec::new());
        for (i, a) in graph.tiles().iter().enumerate() {
            for (j, b) in graph.tiles().iter().enumerate().skip(i + 1) {
                if a.faces.iter().any(|f| b.faces.contains(f)) {
                    continue;
                }
                let (end, course) = grid_relation(nx, a.faces, b.faces);
                if end {
                    ends.push([i, j]);
                }
                if course {
                    apart.push([i, j]);
                }
            }
        }
        assert_eq!(graph.end_to_end(), &ends[..], "{nx} x {ny} end to end");
        assert_eq!(graph.one_course_apart(), &apart[..], "{nx} x {ny} apart");
        // Each bond's relation: its relations' pairs, each once.
        let (herring, w) = graph.bond_pairs(Bond::Herringbone { weight: 0.3 });
        assert_eq!(w, -0.3);
        assert_eq!(herring.len(), graph.continuous_joints().len() + ends.len());
        let (basket, _) = graph.bond_pairs(Bond::BasketWeave { weight: 0.3 });
        assert_eq!(
            basket.len(),
            graph.shifted_pairs().len() + ends.len() + apart.len()
        );
    }
}

#[test]
fn shared_shells_get_valid_patterns_with_an_honest_bound() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/surfaces/quads");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        eprintln!("skipped: {} not found", dir.display());
        return;
    };
    let mut paths: Vec<_> = entries
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "obj"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty());
    for path in paths {
        let mesh = tilepattern::mesh::obj::read(&path).unwrap();
        for bond in [
            Bond::Herringbone { weight: 0.5 },
            Bond::BasketWeave { weight: 0.5 },
        ] {
            let options = {
                let mut o = PatternOptions::default();
                o.bond = bond;
                o.time_limit = Duration::from_secs(3);
                o
            };
            let found = pattern::solve(&mesh, &options).unwrap();
            let name = format!("{} {bond:?}", path.display());
            assert!(common::is_valid_matching(&mesh, &found.pairs), "{name}");
            let graph = DualGraph::new(&mesh, &Topology::new(&mesh).unwrap(), &[]);
            let chosen: Vec<bool> = graph
                .tiles()
                .iter()
                .map(|t| found.pairs.contains(&t.faces))
                .collect();
            let scored = pattern::score(&graph, &chosen, bond).objective;
            assert!((scored - found.objective).abs() < 1e-9, "{name}");
            assert!(found.bound >= found.objective - 1e-9, "{name}");
            // No pattern has more tiles than a face pairs with: the bound is at most that.
            assert!(
                found.bound <= mesh.face_count() as f64 / 2.0 + 1e-9,
                "{name}"
            );
            assert_eq!(
                found.status == SolveStatus::Optimal,
                found.gap <= 1e-9,
                "{name}"
            );
            eprintln!(
                "{name}: {} tiles, objective {}, bound {}, {:?}",
                found.pairs.len(),
                found.objective,
                found.bound,
                found.status
            );
        }
    }
}

#[test]
fn the_command_line_lays_both_bonds_and_refuses_them_in_level_courses() {
    let dir = common::scratch("bonds");
    let quads = dir.join("grid.obj");
    // An 8 x 8 grid of quads of (280 + 10) / 2 mm, half a 280 x 140 mm tile with its joint.
    let mut text = String::new();
    for j in 0..=8 {
        for i in 0..=8 {
            text += &format!("v {} {} 0\n", 145 * i, 145 * j);
        }
    }
    for j in 0..8 {
        for i in 0..8 {
            let v = |i: usize, j: usize| j * 9 + i + 1;
            let corners = [v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)];
            text += &format!(
                "f {} {} {} {}\n",
                corners[0], corners[1], corners[2], corners[3]
            );
        }
    }
    std::fs::write(&quads, text).unwrap();
    for (name, tiles) in [("basket-weave", 32), ("herringbone", 0)] {
        let (json, svg) = (dir.join(format!("{name}.json")), dir.join("p.svg"));
        let out = common::tilepattern(&[
            "match",
            common::s(&quads),
            "--pattern",
            name,
            "--json",
            common::s(&json),
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{name}: {stderr}");
        // The tiles stage keeps the bond and draws it.
        let out = common::tilepattern(&[
            "tiles",
            common::s(&quads),
            "--pairs",
            common::s(&json),
            "--tile",
            "280x140x15",
            "--joint",
            "10",
            "--pattern",
            name,
            "--output",
            common::s(&dir.join("tiles.obj")),
            "--svg",
            common::s(&svg),
        ]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{name} tiles: {stderr}");
        let found = common::json(&json);
        assert_eq!(found["status"], "optimal", "{name}");
        assert!(found["bond_pairs"].is_u64(), "{name}");
        if tiles > 0 {
            // The 8 x 8 basket weave: 16 squares, every face paired, no pair penalised.
            assert_eq!(found["pairs"].as_array().unwrap().len(), tiles);
            assert_eq!(found["bond_pairs"], 0);
        }
        assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
        let level = common::tilepattern(&[
            "match",
            common::s(&quads),
            "--pattern",
            name,
            "--courses",
            "level",
        ]);
        let stderr = String::from_utf8_lossy(&level.stderr);
        assert!(!level.status.success(), "{name}");
        assert!(
            stderr.contains(name) && stderr.contains("courses free"),
            "{name}: {stderr}"
        );
    }
}
