//! TilePattern: laying patterns of standard rectangular tiles on free-form shells that need as
//! little cutting as possible, after Du, Van Mele and Block, "Tile patterning on free-form
//! surfaces that reduces tile cutting" (IASS 2023).
//!
//! The pipeline, one module per stage:
//!
//! 1. [`mesh`]: polygon meshes, validation, OBJ in/out, generated examples;
//! 2. [`pattern`]: match adjacent quads into tiles with the paper's integer programs;
//! 3. [`tiles`]: a box per matched pair, half tiles for unmatched quads;
//! 4. [`report`]: counts, joint gaps and overlaps, pictures;
//!
//! and [`pipeline`] runs them in a row.
//!
//! ```
//! use tilepattern::{mesh, pattern, tiles, report};
//!
//! let quads = mesh::generate::grid(4, 4);
//! let found = pattern::solve(&quads, &pattern::PatternOptions::default()).unwrap();
//! assert_eq!(found.pairs.len(), 8);
//! let spec = tiles::TileSpec { length: 1.9, width: 0.95, thickness: 0.1, joint: 0.1 };
//! let boxes = tiles::build(&quads, &found, &spec).unwrap();
//! let summary = report::Report::new(&quads, &found, &boxes, &spec);
//! assert_eq!(summary.full_tiles, 8);
//! ```
#![deny(missing_docs)]
// Module docs are written for maintainers: they walk through each stage's private modules.
// `cargo doc --document-private-items` (as CI runs it) renders those names as links.
#![allow(rustdoc::private_intra_doc_links)]
#![deny(unsafe_code)]

// COIN-OR built from source and linked statically (feature static-coin, build.rs): naming the
// crates links their archives.
#[cfg(feature = "static-coin")]
extern crate cbc_src as _;
#[cfg(feature = "static-coin")]
extern crate clp_src as _;

pub mod control;
pub mod ffi;
pub(crate) mod geom;
pub mod mesh;
pub(crate) mod parallel;
pub mod pattern;
pub mod pipeline;
pub mod remesh;
pub mod report;
// The outer doc line below keeps cbindgen out of the solver bindings: their Clp
// declarations are imports, not part of our C header.
/// cbindgen:ignore
pub(crate) mod solver;
pub mod tiles;
