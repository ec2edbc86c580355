# Entry points: `make demo` (set up, build, run the demo) and `make test`
# (set up, build, run every test). CMake does the real work in build/.
BUILD ?= build
TYPE ?= RelWithDebInfo
JOBS ?= $(shell nproc)
PREFIX ?= /usr/local

FUZZ_SECONDS ?= 60

.PHONY: all setup configure build debug test demo bench bench-startup fuzz install clean

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

demo: build
	@$(BUILD)/shell/smql demo

bench: build
	@$(BUILD)/bench/smql_bench --out docs/benchmarks.md
	@bench/startup.sh $(BUILD)/shell/smql

# One query in a fresh process, smql next to sqlite3 (the table of docs/benchmarks.md, "Start-up").
bench-startup: build
	@bench/startup.sh $(BUILD)/shell/smql

# libFuzzer targets, built with clang in build-fuzz, each run FUZZ_SECONDS seconds; fails on a crash.
fuzz: setup
	@scripts/fuzz.sh $(FUZZ_SECONDS)

install: build
	@cmake --install $(BUILD)

clean:
	@rm -rf $(BUILD) build-debug build-fuzz
