# TilePattern: the two quick-start commands are `make demo` and `make test`.
CARGO ?= cargo
CC ?= cc
CXX ?= c++
LIB_DIR := target/release
C_FLAGS := -Wall -Wextra -Werror -DTP_TEST_PANIC -Iinclude
C_LINK := -L$(LIB_DIR) -ltilepattern -lm -Wl,-rpath,$(CURDIR)/$(LIB_DIR)

.PHONY: demo test setup build bench header header-check lint rust-test c-test asan-test dotnet-test gh-compile python-test \
	static-check wheel wheel-test package package-test

setup:
	@scripts/setup.sh

build: setup
	$(CARGO) build --release

demo: build
	./target/release/tilepattern demo --out demo

# Every test: the house rules (format, clippy, rustdoc), the header matches the code, the Rust tests, the C tests under valgrind, the C#
# wrapper's NUnit tests under mono, the Grasshopper components compiled against checked
# RhinoCommon/Grasshopper stubs, the Python package's pytest suite and its wheel in a fresh venv,
# the Yak package's layout.
test: setup
	$(MAKE) lint
	scripts/check-header.sh
	$(MAKE) rust-test c-test dotnet-test gh-compile python-test package-test

# House rules: rustfmt's layout, no clippy warning on any target, rustdoc without warnings
# (maintainers' docs, private items included). Checked against the system's shared COIN-OR
# (--no-default-features), so that the check build does not compile COIN-OR from source again;
# the command line (feature cli) is checked with it.
lint:
	$(CARGO) fmt --check
	$(CARGO) clippy --all-targets --no-default-features --features cli -- -D warnings
	RUSTDOCFLAGS="-D warnings" $(CARGO) doc --no-deps --document-private-items --no-default-features --features cli
	@# The library alone depends on nothing only the command line uses.
	@if $(CARGO) tree --no-default-features -e normal --prefix none | grep -E '^(clap|anyhow) '; then \
		echo "lint: the library (without feature cli) depends on the command line's crates above" >&2; exit 1; fi

rust-test:
	$(CARGO) test --release

# The C tests link the cdylib built with the test-panic feature (tp_test_panic), after checking
# that it needs no shared COIN-OR library (static-check). Valgrind runs one thread at a time;
# --fair-sched=yes hands its lock round in turn, so that the caller's thread still polls
# (progress, cancel) every 20 ms while CBC computes on the solver thread: without it the
# poller could wait out a whole CBC solve and the cancel test found the solve finished.
VALGRIND := valgrind --fair-sched=yes --error-exitcode=1 --leak-check=full --errors-for-leak-kinds=definite,indirect,possible \
	--suppressions=tests/c/valgrind.supp
c-test:
	$(CARGO) build --release --lib --features test-panic
	scripts/check-static.sh $(LIB_DIR)/libtilepattern.so
	mkdir -p target/c
	$(CC) -std=c11 $(C_FLAGS) tests/c/test_tilepattern.c $(C_LINK) -o target/c/test_c
	$(CXX) -std=c++17 $(C_FLAGS) -x c++ tests/c/test_tilepattern.c $(C_LINK) -o target/c/test_cpp
	RUST_BACKTRACE=0 target/c/test_cpp
	RUST_BACKTRACE=0 TP_TEST_TIME_SCALE=50 $(VALGRIND) --show-leak-kinds=definite,indirect,possible target/c/test_c
	$(CC) -std=c11 $(C_FLAGS) tests/c/test_bad_input.c $(C_LINK) -o target/c/test_bad_input
	$(CXX) -std=c++17 $(C_FLAGS) -x c++ tests/c/test_bad_input.c $(C_LINK) -o target/c/test_bad_input_cpp
	RUST_BACKTRACE=0 target/c/test_bad_input_cpp
	RUST_BACKTRACE=0 $(VALGRIND) --quiet target/c/test_bad_input

# The C tests under AddressSanitizer (leaks included): the library built with
# -Zsanitizer=address in target/asan (a nightly flag: RUSTC_BOOTSTRAP=1 lets the stable
# toolchain take it; --target keeps build scripts uninstrumented), the tests with
# -fsanitize=address. Not part of `make test`: it builds every dependency again (~2 min).
HOST := $(shell rustc -vV | sed -n 's/^host: //p')
ASAN_LIB := target/asan/$(HOST)/release
ASAN_LINK := -fsanitize=address -fno-omit-frame-pointer -L$(ASAN_LIB) -ltilepattern -lm -Wl,-rpath,$(CURDIR)/$(ASAN_LIB)
asan-test:
	RUSTC_BOOTSTRAP=1 RUSTFLAGS="-Zsanitizer=address" $(CARGO) build --release --lib --features test-panic \
		--target $(HOST) --target-dir target/asan
	mkdir -p target/c
	$(CC) -std=c11 $(C_FLAGS) tests/c/test_tilepattern.c $(ASAN_LINK) -o target/c/test_c_asan
	$(CC) -std=c11 $(C_FLAGS) tests/c/test_bad_input.c $(ASAN_LINK) -o target/c/test_bad_input_asan
	RUST_BACKTRACE=0 target/c/test_c_asan
	RUST_BACKTRACE=0 target/c/test_bad_input_asan

# The C# wrapper (dotnet/) compiled with mcs, its NUnit tests run under mono.
dotnet-test:
	$(CARGO) build --release --lib
	scripts/test-dotnet.sh

# The Grasshopper components (grasshopper/) compiled with mcs, warnings as errors, against
# reference stubs of RhinoCommon and Grasshopper that scripts/check-gh-stubs.py checks member by
# member against the published type stubs (PyPI); plus a self-test that broken stubs fail.
gh-compile:
	scripts/gh-compile.sh

# The Python package (python/) in a venv under target/, tested with pytest; then the wheel
# (wheel-test).
python-test:
	$(CARGO) build --release --lib
	scripts/test-python.sh
	$(MAKE) wheel-test

# The native library of a release build links COIN-OR statically: ldd lists no COIN-OR library.
static-check:
	$(CARGO) build --release --lib
	scripts/check-static.sh $(LIB_DIR)/libtilepattern.so

# A Python wheel carrying the native library: target/wheels/tilepattern-VERSION-py3-none-PLATFORM.whl.
wheel:
	$(CARGO) build --release --lib
	scripts/wheel.sh

# The wheel installed into a fresh venv outside the repository, no environment variable:
# python/README.md's example runs and writes a .3dm.
wheel-test: wheel
	scripts/test-wheel.sh

# The Yak package folder of the Grasshopper plug-in in target/yak/ (manifest, .gha, wrapper,
# runtimes/<rid>/native/), checked; `yak build` there (Rhino's tool) makes the .yak.
package: gh-compile
	$(CARGO) build --release --lib
	scripts/package.sh

# make package, then broken copies of the folder must fail the check.
package-test: gh-compile
	$(CARGO) build --release --lib
	scripts/test-package.sh

header:
	cbindgen --quiet --config cbindgen.toml --crate tilepattern --output include/tilepattern.h

bench: setup
	$(CARGO) bench --bench matching
