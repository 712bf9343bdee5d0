//! The solid of a placed tile: its kept face extruded through its thickness. An uncut tile
//! is its box; a cut tile is each piece of its kept outline (outer loops with the holes
//! inside them) as a prism, its top and bottom triangulated (ear clipping, `earcut`), so
//! that what a drawing or a model shows is the piece a mason cuts, not the blank.

use nalgebra::{Point3, Vector3};

use super::Tile;
use crate::geom::polygon::{self, Point2};

/// A closed, outward-oriented polygon mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Solid {
    /// Corner positions.
    pub positions: Vec<Point3<f64>>,
    /// Faces as corner indices, counter-clockwise seen from outside.
    pub faces: Vec<Vec<usize>>,
}

/// The solid of `tile`: its box, or the prisms of the pieces of its kept outline.
pub fn solid(tile: &Tile) -> Solid {
    let Some(cut) = &tile.cut else {
        const BOX_FACES: [[usize; 4]; 6] = [
            [0, 3, 2, 1],
            [4, 5, 6, 7],
            [0, 1, 5, 4],
            [1, 2, 6, 5],
            [2, 3, 7, 6],
            [3, 0, 4, 7],
        ];
        return Solid {
            positions: tile.corners.iter().map(|c| Point3::from(*c)).collect(),
            faces: BOX_FACES.iter().map(|f| f.to_vec()).collect(),
        };
    };
    let mut out = Solid {
        positions: Vec::new(),
        faces: Vec::new(),
    };
    let (outer, holes): (Vec<&Vec<Point2>>, Vec<&Vec<Point2>>) = cut
        .loops
        .iter()
        .filter(|l| l.len() >= 3)
        .partition(|l| polygon::signed_area(l) > 0.0);
    for piece in &outer {
        let inside: Vec<&Vec<Point2>> = holes
            .iter()
            .copied()
            .filter(|h| polygon::winding(&[piece.to_vec()], h[0]) != 0)
            .collect();
        prism(tile, piece, &inside, &mut out);
    }
    out
}

/// Adds the prism of one piece (an outer loop counter-clockwise, holes clockwise) of `tile`.
fn prism(tile: &Tile, outer: &[Point2], holes: &[&Vec<Point2>], out: &mut Solid) {
    let mut ring: Vec<Point2> = outer.to_vec();
    let mut starts: Vec<usize> = Vec::new();
    for h in holes {
        starts.push(ring.len());
        ring.extend(h.iter());
    }
    let mut triangles: Vec<usize> = Vec::new();
    earcut::Earcut::new().earcut(ring.iter().copied(), &starts, &mut triangles);
    let base = out.positions.len();
    let n = ring.len();
    let thickness = tile.size[2];
    for z in [0.0, thickness] {
        out.positions.extend(
            ring.iter()
                .map(|p| tile.to_world(Vector3::new(p[0], p[1], z))),
        );
    }
    for t in triangles.chunks_exact(3) {
        // Earcut returns triangles in the rings' own turning sense (counter-clockwise here):
        // the bottom is seen from below, so it turns the other way.
        out.faces.push(vec![base + t[0], base + t[2], base + t[1]]);
        out.faces
            .push(vec![base + n + t[0], base + n + t[1], base + n + t[2]]);
    }
    // Walls: every edge of every ring (holes run clockwise, so their walls face inwards).
    let mut bounds: Vec<(usize, usize)> = Vec::new();
    let mut from = 0;
    for &s in starts.iter().chain(std::iter::once(&n)) {
        bounds.push((from, s));
        from = s;
    }
    for (a, b) in bounds {
        for i in a..b {
            let j = if i + 1 == b { a } else { i + 1 };
            out.faces
                .push(vec![base + i, base + j, base + n + j, base + n + i]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tiles::{Cut, Frame, TileKind};

    fn flat_tile(cut: Option<Cut>) -> Tile {
        let frame = Frame {
            origin: Point3::origin(),
            x: Vector3::x(),
            y: Vector3::y(),
            z: Vector3::z(),
        };
        let mut tile = Tile::new(TileKind::Full, vec![0, 1], frame, [2.0, 1.0, 0.1]);
        tile.cut = cut;
        tile
    }

    /// Volume of a closed mesh by the divergence theorem (positive when outward-oriented).
    fn volume(s: &Solid) -> f64 {
        s.faces
            .iter()
            .map(|f| {
                (1..f.len() - 1)
                    .map(|k| {
                        s.positions[f[0]].coords.dot(
                            &s.positions[f[k]]
                                .coords
                                .cross(&s.positions[f[k + 1]].coords),
                        ) / 6.0
                    })
                    .sum::<f64>()
            })
            .sum()
    }

    #[test]
    fn a_box_and_a_cut_tile_are_closed_and_outward() {
        assert!((volume(&solid(&flat_tile(None))) - 0.2).abs() < 1e-12);
        // An L-shaped piece: the rectangle without its top-right quarter.
        let l = vec![
            [-1.0, -0.5],
            [1.0, -0.5],
            [1.0, 0.0],
            [0.0, 0.0],
            [0.0, 0.5],
            [-1.0, 0.5],
        ];
        let s = solid(&flat_tile(Some(Cut {
            loops: vec![l],
            kept_fraction: 0.75,
        })));
        assert!((volume(&s) - 0.15).abs() < 1e-12);
    }

    #[test]
    fn holes_and_several_pieces_are_kept() {
        let outer = vec![[-1.0, -0.5], [1.0, -0.5], [1.0, 0.5], [-1.0, 0.5]];
        let hole = vec![[-0.2, -0.2], [-0.2, 0.2], [0.2, 0.2], [0.2, -0.2]];
        let s = solid(&flat_tile(Some(Cut {
            loops: vec![outer, hole],
            kept_fraction: 0.92,
        })));
        assert!((volume(&s) - 0.1 * (2.0 - 0.16)).abs() < 1e-12);
        let left = vec![[-1.0, -0.5], [-0.5, -0.5], [-0.5, 0.5], [-1.0, 0.5]];
        let right = vec![[0.5, -0.5], [1.0, -0.5], [1.0, 0.5], [0.5, 0.5]];
        let s = solid(&flat_tile(Some(Cut {
            loops: vec![left, right],
            kept_fraction: 0.5,
        })));
        assert!((volume(&s) - 0.1).abs() < 1e-12);
    }
}
