# TilePattern: the two quick-start commands are `make demo` and `make test`.
CARGO ?= cargo

.PHONY: demo test setup build bench

setup:
	@scripts/setup.sh

build: setup
	$(CARGO) build --release

demo: build
	./target/release/tilepattern demo --out demo

test: setup
	$(CARGO) test --release

bench: setup
	$(CARGO) bench --bench matching
