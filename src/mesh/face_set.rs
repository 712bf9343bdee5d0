//! Faces told apart by their corners alone (as a set, whatever their order or winding): the
//! one test behind a face given twice, which welding drops and validation refuses.

use std::collections::HashMap;

use foldhash::fast::FixedState;

/// A face's corners as a set: sorted, each once.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub(crate) enum Corners {
    /// Up to four corners (triangles and quads, most faces): no allocation. Padded with
    /// `usize::MAX`.
    Small([usize; 4]),
    /// More.
    Large(Vec<usize>),
}

impl Corners {
    /// The set of `corners`.
    pub fn of(corners: &[usize]) -> Self {
        if corners.len() <= 4 {
            let mut key = [usize::MAX; 4];
            key[..corners.len()].copy_from_slice(corners);
            key.sort_unstable();
            let mut kept = 0;
            for k in 0..corners.len() {
                if kept == 0 || key[k] != key[kept - 1] {
                    key[kept] = key[k];
                    kept += 1;
                }
            }
            key[kept..].fill(usize::MAX);
            return Self::Small(key);
        }
        let mut key = corners.to_vec();
        key.sort_unstable();
        key.dedup();
        if key.len() <= 4 {
            return Self::of(&key);
        }
        Self::Large(key)
    }

    /// How many different corners.
    pub fn len(&self) -> usize {
        match self {
            Self::Small(key) => key.iter().filter(|&&v| v != usize::MAX).count(),
            Self::Large(key) => key.len(),
        }
    }
}

/// Faces seen so far, each under its set of corners.
pub(crate) struct FaceSet {
    /// A fixed-seed hasher: only lookups, never the map's order, shape a result.
    first: HashMap<Corners, usize, FixedState>,
}

impl FaceSet {
    /// Room for about `faces` faces.
    pub fn with_capacity(faces: usize) -> Self {
        Self {
            first: HashMap::with_capacity_and_hasher(faces, FixedState::default()),
        }
    }

    /// Records face number `face` under `corners`, unless a face with the same set of
    /// corners was recorded before: then returns that face's number and records nothing.
    pub fn insert(&mut self, corners: Corners, face: usize) -> Option<usize> {
        match self.first.entry(corners) {
            std::collections::hash_map::Entry::Occupied(e) => Some(*e.get()),
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(face);
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_same_corners_in_any_order_are_the_same_face() {
        let mut set = FaceSet::with_capacity(4);
        let mut insert = |corners: &[usize], face| set.insert(Corners::of(corners), face);
        assert_eq!(insert(&[0, 1, 2], 0), None);
        assert_eq!(insert(&[2, 1, 0], 1), Some(0));
        assert_eq!(insert(&[1, 2, 0, 3], 2), None);
        assert_eq!(insert(&[3, 0, 2, 1], 3), Some(2));
        // A repeated corner counts once, in small faces and large ones alike.
        assert_eq!(insert(&[0, 0, 1, 2], 4), Some(0));
        assert_eq!(insert(&[5, 6, 7, 8, 9], 5), None);
        assert_eq!(insert(&[9, 8, 7, 6, 5, 5], 6), Some(5));
        assert_eq!(insert(&[1, 2, 2, 1, 0, 0], 7), Some(0));
        assert_eq!(insert(&[1, 1, 1, 2], 8), None);
        assert_eq!(insert(&[2, 1], 9), Some(8));
    }

    #[test]
    fn counts_different_corners() {
        assert_eq!(Corners::of(&[3, 3, 3, 4]).len(), 2);
        assert_eq!(Corners::of(&[1, 2, 3, 4, 4, 4, 1]).len(), 4);
        assert_eq!(Corners::of(&[1, 2, 3, 4, 5]).len(), 5);
        assert_eq!(Corners::of(&[1, 2, 3, 4, 5]), Corners::of(&[5, 4, 3, 2, 1]));
    }
}
