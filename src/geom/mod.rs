//! Shared geometry: the one spatial index of each kind, closest points on a surface, and the
//! segment and polygon helpers every stage uses.
//!
//! - [`Bvh`]: a bounding volume hierarchy for nearest-primitive queries (closest point on a
//!   surface or a boundary);
//! - [`HashGrid`]: a sparse grid of cells for "what lies near here" queries over items of
//!   about one cell's size (tiles, a surface's faces and boundary edges);
//! - [`closest`]: closest points on segments and triangles;
//! - [`SurfaceIndex`]: closest point and smooth normal on a polygon mesh;
//! - [`polygon`]: points and polygons in a plane (areas, convex clipping, separation).
//!
//! Nothing here knows of tiles, quads or patterns: stages build on it, never the reverse.

mod bvh;
pub mod closest;
mod grid;
pub mod polygon;
mod surface;

pub use bvh::Bvh;
pub use grid::HashGrid;
pub use surface::{SurfaceIndex, SurfacePoint};
