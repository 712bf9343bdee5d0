//! How the COIN-OR solvers (CBC for the matching programs, Clp for the barrier relaxations,
//! and CoinUtils, Osi, Cgl beneath them) are linked.
//!
//! - Feature `static-coin` (default): the `cbc-src` and `clp-src` crates compile COIN-OR from
//!   source, position-independent, into static archives that are linked into the library and
//!   the CLI, so that neither needs a COIN-OR library at run time (`ldd` lists none). Nothing
//!   to do here; `src/lib.rs` names the crates so that they are linked.
//! - Without it (`--no-default-features`): the system's shared libraries, found by pkg-config
//!   (`cbc` and `clp`; Debian: coinor-libcbc-dev, coinor-libclp-dev).
//!
//! Debian's static archives (`/usr/lib/x86_64-linux-gnu/libCbc.a`, ...) cannot be used: they are
//! compiled as position-independent executables, not position-independent code, and a shared
//! library cannot hold them (the linker refuses `R_X86_64_PC32` relocations against `stdout`).

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    if std::env::var_os("CARGO_FEATURE_STATIC_COIN").is_some() {
        return;
    }
    for library in ["cbc", "clp"] {
        if let Err(error) = pkg_config::probe_library(library) {
            println!(
                "cargo:warning=pkg-config did not find {library} ({error}); install the COIN-OR \
                 development packages (Debian: coinor-libcbc-dev coinor-libclp-dev) or build with \
                 the default feature static-coin"
            );
        }
    }
}
