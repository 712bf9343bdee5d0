//! How the COIN-OR solvers (CBC for the matching programs, Clp for the barrier relaxations,
//! and CoinUtils, Osi, Cgl beneath them) are linked, and the small C++ shim that lets a caller
//! stop them (`src/solver/watch.cpp`: CBC's and Clp's event handlers), compiled against the
//! headers of the COIN-OR that is linked.
//!
//! - Feature `static-coin` (default): the `cbc-src` and `clp-src` crates compile COIN-OR from
//!   source, position-independent, into static archives that are linked into the library and
//!   the CLI, so that neither needs a COIN-OR library at run time (`ldd` lists none);
//!   `src/lib.rs` names the crates so that they are linked. Their build scripts publish their
//!   header directories and the `COIN_HAS_*` flags they compiled with (`DEP_CBC_INCLUDE`,
//!   `DEP_CBC_COINFLAGS`); the shim is compiled with the same.
//! - Without it (`--no-default-features`): the system's shared libraries, found by pkg-config
//!   (`cbc` and `clp`; Debian: coinor-libcbc-dev, coinor-libclp-dev), and their headers.
//!
//! Debian's static archives (`/usr/lib/x86_64-linux-gnu/libCbc.a`, ...) cannot be used: they are
//! compiled as position-independent executables, not position-independent code, and a shared
//! library cannot hold them (the linker refuses `R_X86_64_PC32` relocations against `stdout`).

use std::path::PathBuf;

const SHIM: &str = "src/solver/watch.cpp";

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed={SHIM}");
    let mut shim = cc::Build::new();
    shim.cpp(true)
        .std("c++11")
        .file(SHIM)
        .define("NDEBUG", None)
        .warnings(false);
    if std::env::var_os("CARGO_FEATURE_STATIC_COIN").is_some() {
        // The defines the -src crates compile COIN-OR with (coin-build-tools), so that the
        // classes' layouts agree.
        for define in [
            "HAVE_STDIO_H",
            "HAVE_STDLIB_H",
            "HAVE_STRING_H",
            "HAVE_INTTYPES_H",
            "HAVE_STDINT_H",
            "HAVE_STRINGS_H",
            "HAVE_SYS_TYPES_H",
            "HAVE_SYS_STAT_H",
            "HAVE_UNISTD_H",
            "HAVE_CMATH",
            "HAVE_CFLOAT",
            "HAVE_MEMORY_H",
        ] {
            shim.define(define, None);
        }
        let includes = std::env::var_os("DEP_CBC_INCLUDE")
            .expect("cbc-src publishes its header directories (DEP_CBC_INCLUDE)");
        shim.includes(std::env::split_paths(&includes));
        let flags = std::env::var("DEP_CBC_COINFLAGS").unwrap_or_default();
        let mut flags: Vec<&str> = flags.split(';').filter(|f| !f.is_empty()).collect();
        flags.sort_unstable();
        flags.dedup();
        for flag in flags {
            shim.define(&format!("COIN_HAS_{flag}"), None);
        }
    } else {
        let mut includes: Vec<PathBuf> = Vec::new();
        for library in ["cbc", "clp"] {
            match pkg_config::probe_library(library) {
                Ok(found) => includes.extend(found.include_paths),
                Err(error) => println!(
                    "cargo:warning=pkg-config did not find {library} ({error}); install the \
                     COIN-OR development packages (Debian: coinor-libcbc-dev \
                     coinor-libclp-dev) or build with the default feature static-coin"
                ),
            }
        }
        includes.dedup();
        shim.includes(includes);
    }
    shim.compile("tilepattern_coin_watch");
}
