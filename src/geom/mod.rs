//! Shared geometry: the one spatial index of each kind, closest points on a surface, and the
//! segment and polygon helpers every stage uses.
//!
//! - [`Bvh`]: a bounding volume hierarchy for nearest-primitive queries (closest point on a
//!   surface or a boundary);
//! - [`HashGrid`]: a sparse grid of cells for "what lies near here" queries over items of
//!   about one cell's size (tiles, a surface's faces and boundary edges);
//! - [`closest`]: closest points on segments and triangles;
//! - [`SurfaceIndex`]: closest point and smooth normal on a polygon mesh;
//! - [`polygon`]: points and polygons in a plane (areas, convex clipping, separation);
//! - [`sample`]: area samples of a surface.
//!
//! Nothing here knows of tiles, quads or patterns: stages build on it, never the reverse.

mod bvh;
pub mod closest;
mod grid;
pub mod polygon;
pub mod sample;
mod surface;

pub use bvh::Bvh;
pub use grid::HashGrid;
pub use surface::{SurfaceIndex, fan};

/// Deterministic pseudo-random numbers in [0, 1) for tests (a 64-bit linear congruential
/// generator, the top 53 bits).
#[cfg(test)]
pub(crate) fn numbers(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}
