//! Orientation: turning faces so that every face runs each edge it shares with a neighbour
//! the other way round, as a surface with one top side needs (a tile is laid on the side the
//! normals point to). Files put together from several patches, or exported by tools that do
//! not keep winding, often have some faces the wrong way round; on a two-sided (orientable)
//! surface the fix is unique up to turning a whole piece over, and this keeps, in every piece,
//! the side most of its faces already face.

use super::MeshError;

/// Turns faces (reverses their corners after the first) so that neighbours agree: two faces
/// sharing an edge run it in opposite directions. Each piece (faces joined across edges that
/// exactly two faces share) keeps the orientation most of its faces have; on a tie, that of
/// its first face. Edges with one face or more than two are no links (validation names the
/// latter). Returns how many faces were turned; `faces` is unchanged on an error.
///
/// # Errors
/// [`MeshError::NonOrientable`] when a piece is one-sided (a Moebius strip): no choice of
/// sides makes every pair of neighbours agree.
pub fn orient(faces: &mut [Vec<usize>]) -> Result<usize, MeshError> {
    let links = links(faces);
    let mut turn: Vec<Option<bool>> = vec![None; faces.len()];
    let mut to_turn = Vec::new();
    let mut piece = Vec::new();
    let mut stack = Vec::new();
    for root in 0..faces.len() {
        if turn[root].is_some() {
            continue;
        }
        turn[root] = Some(false);
        piece.clear();
        stack.push(root);
        while let Some(f) = stack.pop() {
            piece.push(f);
            let turned = turn[f] == Some(true);
            for &(g, same_direction) in &links[f] {
                // g must run the edge against f once both are turned as decided.
                let wanted = turned ^ same_direction;
                match turn[g] {
                    None => {
                        turn[g] = Some(wanted);
                        stack.push(g);
                    }
                    Some(t) if t != wanted => {
                        return Err(MeshError::NonOrientable {
                            faces: [f.min(g), f.max(g)],
                        });
                    }
                    Some(_) => {}
                }
            }
        }
        let turned = piece.iter().filter(|&&f| turn[f] == Some(true)).count();
        // Keep the side most faces of the piece face (the root's on a tie).
        let keep_turned = turned * 2 > piece.len();
        to_turn.extend(
            piece
                .iter()
                .copied()
                .filter(|&f| (turn[f] == Some(true)) != keep_turned),
        );
    }
    for &f in &to_turn {
        faces[f][1..].reverse();
    }
    Ok(to_turn.len())
}

/// For every face, its neighbours across edges exactly two faces share, each with whether
/// both run that edge in the same direction. Sorted, so the result does not depend on hashing.
fn links(faces: &[Vec<usize>]) -> Vec<Vec<(usize, bool)>> {
    // (low vertex, high vertex, face, whether the face runs low -> high)
    let mut sides: Vec<(usize, usize, usize, bool)> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        for (i, &a) in face.iter().enumerate() {
            let b = face[(i + 1) % face.len()];
            if a != b {
                sides.push((a.min(b), a.max(b), f, a < b));
            }
        }
    }
    sides.sort_unstable();
    let mut links = vec![Vec::new(); faces.len()];
    for run in sides.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        if let [(_, _, f, f_up), (_, _, g, g_up)] = *run
            && f != g
        {
            links[f].push((g, f_up == g_up));
            links[g].push((f, f_up == g_up));
        }
    }
    links
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether every edge two faces share is run in opposite directions by them.
    fn consistent(faces: &[Vec<usize>]) -> bool {
        links(faces).iter().flatten().all(|&(_, same)| !same)
    }

    /// An `n` x `n` grid of quads, every face counter-clockwise seen from +z.
    fn grid(n: usize) -> Vec<Vec<usize>> {
        let v = |i: usize, j: usize| j * (n + 1) + i;
        (0..n)
            .flat_map(|j| {
                (0..n).map(move |i| vec![v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)])
            })
            .collect()
    }

    #[test]
    fn the_faces_against_the_majority_are_turned_and_no_others() {
        let good = grid(4);
        let mut faces = good.clone();
        for f in [3, 5, 6, 11] {
            faces[f][1..].reverse();
        }
        assert!(!consistent(&faces));
        assert_eq!(orient(&mut faces), Ok(4));
        assert_eq!(faces, good);
        // Already consistent: nothing to do.
        assert_eq!(orient(&mut faces), Ok(0));
    }

    #[test]
    fn each_piece_keeps_the_side_most_of_its_faces_face() {
        // Two grids side by side sharing no edge: the second mostly turned over.
        let mut faces = grid(2);
        let offset = 9;
        let mut second: Vec<Vec<usize>> = grid(2)
            .into_iter()
            .map(|f| f.into_iter().map(|v| v + offset).collect())
            .collect();
        for f in &mut second[..3] {
            f[1..].reverse();
        }
        // The three turned faces decide; the fourth is turned to join them.
        let mut expected_second = second.clone();
        expected_second[3][1..].reverse();
        faces.extend(second);
        assert_eq!(orient(&mut faces), Ok(1));
        assert!(consistent(&faces));
        assert_eq!(faces[..4], grid(2)[..]);
        assert_eq!(faces[4..], expected_second[..]);
    }

    #[test]
    fn a_moebius_strip_is_refused_and_left_as_it_was() {
        // A strip of 6 quads whose ends are joined with a half twist.
        let n = 6;
        let top = |i: usize| 2 * (i % n);
        let bottom = |i: usize| 2 * (i % n) + 1;
        let mut faces: Vec<Vec<usize>> = (0..n - 1)
            .map(|i| vec![bottom(i), bottom(i + 1), top(i + 1), top(i)])
            .collect();
        // The last quad joins the end to the start turned over: top to bottom.
        faces.push(vec![bottom(n - 1), top(0), bottom(0), top(n - 1)]);
        let before = faces.clone();
        let error = orient(&mut faces).unwrap_err();
        assert!(matches!(error, MeshError::NonOrientable { .. }), "{error}");
        assert!(error.to_string().contains("one-sided"), "{error}");
        assert_eq!(faces, before);
        // Given as arrays (the C ABI, C#, Python), it is refused for the same reason, not
        // with advice to unify the normals.
        let positions = (0..2 * n)
            .map(|v| {
                let angle = std::f64::consts::TAU * (v / 2) as f64 / n as f64;
                let radius = 2.0 + (v % 2) as f64;
                nalgebra::Point3::new(radius * angle.cos(), radius * angle.sin(), 0.0)
            })
            .collect();
        let refused = super::super::PolyMesh::new(positions, faces).unwrap_err();
        assert!(
            matches!(refused, MeshError::NonOrientable { .. }),
            "{refused}"
        );
    }
}
