# Entry points: `make demo` (set up, build, run the demo) and `make test`
# (set up, build, run every test). CMake does the real work in build/.
BUILD ?= build
TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc)
PREFIX ?= /usr/local

FUZZ_SECONDS ?= 60

.PHONY: all setup configure build debug test demo bench bench-startup bench-similar bench-python bench-fleet bench-import bench-matching fuzz stress format lint install clean

all: build

setup:
	@scripts/setup.sh

configure: setup
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(TYPE) -DCMAKE_INSTALL_PREFIX=$(PREFIX) >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

debug:
	@$(MAKE) --no-print-directory build BUILD=build-debug TYPE=Debug

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The demo installs smql (under PREFIX) first, so that `smql`, the C library and `import smql` in
# python3 work from anywhere afterwards.
demo: install
	@$(BUILD)/shell/smql demo

bench: build
	@$(BUILD)/bench/smql_bench --out docs/benchmarks.md
	@bench/startup.sh $(BUILD)/shell/smql

# One query in a fresh process, smql next to sqlite3 (the table of docs/benchmarks.md, "Start-up").
bench-startup: build
	@bench/startup.sh $(BUILD)/shell/smql

# The Python package against the C API and Python's sqlite3 (docs/benchmarks.md, "Python").
bench-python: build
	@/usr/bin/python3 bench/python_bench.py $(BUILD) ../shared/data --out docs/benchmarks.md

# SIMILAR TO's search against a scan of every node's vector (docs/benchmarks.md, "SIMILAR TO").
bench-similar: build
	@$(BUILD)/bench/smql_bench_similar

# Imports at n, 2n and 4n: a cost that grows with the square shows as a 4x step (docs/benchmarks.md).
bench-import: build
	@/usr/bin/python3 bench/import_scaling.py $(BUILD)/shell/smql ../shared/data --out docs/benchmarks.md

# Push throughput into a fleet store in a private PostgreSQL cluster (docs/fleet.md, "Measured").
bench-fleet: build
	@$(BUILD)/bench/smql_bench_fleet

# The ingest's feature matching against COLMAP's matcher on ../shared's real photos (docs/benchmarks.md,
# "Feature matching").
bench-matching: build
	@bench/matching.sh $(BUILD)

# libFuzzer targets, built with clang in build-fuzz, each run FUZZ_SECONDS seconds; fails on a crash.
fuzz: setup
	@scripts/fuzz.sh $(FUZZ_SECONDS)

# The fault tests that take minutes (scripts/stress.py; docs/testing.md, "Stress"): SIGKILL during
# STRESS_RUNS imports and ingests, one writer beside eight readers for STRESS_SECONDS, then
# STRESS_FLIPS single-bit flips of a database, each followed by check and every class of read, then
# STRESS_FLEET_KILLS pushes to a fleet store killed at random moments (docs/fleet.md).
STRESS_RUNS ?= 200
STRESS_SECONDS ?= 300
STRESS_FLIPS ?= 1000
STRESS_FLEET_KILLS ?= 100
stress: build
	@scripts/stress.py $(BUILD)/shell/smql kill --runs $(STRESS_RUNS)
	@scripts/stress.py $(BUILD)/shell/smql readers --seconds $(STRESS_SECONDS) --readers 8
	@scripts/stress.py $(BUILD)/shell/smql flips --flips $(STRESS_FLIPS)
	@cd $(BUILD) && SMQL_FLEET_KILLS=$(STRESS_FLEET_KILLS) SMQL_FLEET_PROGRAM=shell/smql-fleet \
		tests/fleet/smql_fleet_tests "pushes killed at random moments leave no partial or duplicated scene"

# The house format (.clang-format): `make format` rewrites the sources, `make lint` checks the format
# and runs clang-tidy's short list (.clang-tidy); the test run includes lint as the test `lint`.
format: setup
	@scripts/sources.sh | xargs clang-format -i

lint: configure
	@scripts/lint.sh $(BUILD)

install: build
	@cmake --install $(BUILD)

clean:
	@rm -rf $(BUILD) build-debug build-fuzz
