//! Outgoing bindings to the COIN-OR solvers the pattern stage calls (paper section 3.4:
//! the programs of eqs. 1-3 are solved by an integer solver; their linear relaxations give
//! bounds). This is the only module of the crate that calls out to C itself; `ffi` holds
//! only our own exports.
//!
//! * [`clp`](crate::solver::clp): Clp's interior-point method through Clp's C interface,
//!   for the linear relaxation and its row prices. Its declarations are ours, so that module
//!   alone allows `unsafe` (every block states why it is sound); the rest of the crate
//!   denies it.
//!
//! Stages build their programs in their own terms and hand them over in the plain
//! column-major form these functions take; nothing here knows of tiles or bonds.

#[allow(unsafe_code)]
pub(crate) mod clp;
