# The two commands of the README, on a fresh Debian machine:
#   make demo   runs the main job: `mcstat reproduce` on the paper's scene,
#               writing report/report.md (figures) and report/results.json
#   make test   builds everything and passes the tests (ci/test-steps.mk)
# Only these two install anything: first the Debian packages they need
# (tools/deps-debian.sh, only those missing), then the Python packages
# through pip into ./.venv.  Every other target builds and runs with what is
# there; `tools/deps-debian.sh TARGET` installs what TARGET needs.

SHELL := /bin/bash
BUILD ?= build
VENV ?= .venv
PY := $(VENV)/bin/python
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: asan-test tsan-test valgrind-test abi-check portability-test
.PHONY: fuzz fuzz-build fuzz-replay fuzz-report
.PHONY: accuracy accuracy-refs
.PHONY: docs docs-c docs-python docs-rust docs-go binding-coverage
.PHONY: all deps python-deps build test ctest python pytest wheel-test wheel-test-extra wheels sdist-test install-test vendor-test ctypes-test rust-deps go-deps rust-test go-test quickstart-test mitsuba-test demo demo-quick demo-c bench bench-check bench-python bench-estimators bench-power references clean

all: build

# ---- dependencies ----------------------------------------------------------
# The Debian packages of make test (tools/deps-debian.sh lists them), and
# requirements-dev.txt in .venv.
deps:
	tools/deps-debian.sh test
	$(MAKE) python-deps

$(VENV)/.installed: requirements-dev.txt
	python3 -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -r requirements-dev.txt
	touch $@

python-deps: $(VENV)/.installed

# ---- build, test, demo -------------------------------------------------------
build:
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)
	cmake --build $(BUILD) -j $(JOBS)

ctest: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Every function the built library exports is reached by every binding, or
# exempted with a reason (tests/bindings/check_coverage.py; COVERAGE_LANGS=python
# checks a subset).
binding-coverage: build
	python3 tests/bindings/check_coverage.py $(BUILD)/libmcstat/libmcstat.so $(foreach l,$(COVERAGE_LANGS),--lang $(l))

# The Python package, built by scikit-build-core through the same CMake,
# installed into .venv.  The CMake build directory is kept in
# $(BUILD)/python/ (pyproject.toml leaves it to a temporary one) so that a
# rebuild recompiles only what changed.
PY_BUILD_DIR := -Cbuild-dir=$(abspath $(BUILD))/python/{wheel_tag}
python: python-deps
	CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) $(PY) -m pip install -q --no-build-isolation $(PY_BUILD_DIR) .

pytest: python
	$(PY) -m pytest -q tests/python

# The binary wheel as another Linux machine gets it: built from the same
# CMake directory as make python, repaired by auditwheel (GSL and libRmath
# bundled, a manylinux tag), installed with its extras into a bare venv and
# run there with LD_LIBRARY_PATH empty (tests/wheel/test_wheel.sh).  Each
# step's cost: bench/RESULTS_gate.md.
wheel-test: python
	JOBS=$(JOBS) tests/wheel/test_wheel.sh $(BUILD) $(PY)

# One more CPython in the gate: WHEEL_EXTRA_PYTHON's wheel, built like
# wheel-test's (system toolchain, auditwheel bundling GSL and libRmath), in a
# bare venv of that interpreter: mcstat reproduce --quick
# (tests/wheel/test_wheel_extra.sh).  A fixed interpreter, never skipped:
# missing, the step fails.
WHEEL_EXTRA_PYTHON ?= $(HOME)/.pyenv/versions/3.13.0/bin/python3
wheel-test-extra: python-deps
	JOBS=$(JOBS) tests/wheel/test_wheel_extra.sh $(BUILD) $(PY) $(WHEEL_EXTRA_PYTHON)

# Wheels for CPython 3.9-3.13 at manylinux_2_28, for publishing; not part of
# make test (ci/test-steps.mk).  zig (PyPI's ziglang) compiles for glibc 2.28:
# GSL and libRmath from Debian's source packages (checked, cached in
# $(BUILD)/wheels/), linked static into the extension; one wheel per pyenv
# interpreter (~/.pyenv/versions/3.X.*), auditwheel repair and show, each
# tested in a bare venv of its interpreter; the pixel and module tests on
# WHEELS_PYTEST's wheel; each wheel's mcstat reproduce --quick results
# compared with those of .venv's gcc build (make python, if installed);
# results in bench/RESULTS_wheels.md
# (tools/wheels/build_wheels.sh).  WHEEL_PYTHONS="3.12 3.13" builds a few.
WHEEL_PYTHONS ?= 3.9 3.10 3.11 3.12 3.13
WHEELS_PYTEST ?= 3.12
wheels: python-deps
	JOBS=$(JOBS) WHEELS_DIR=$(BUILD)/wheels AUDITWHEEL=$(abspath $(VENV))/bin/auditwheel \
	  WHEELS_PYTEST=$(WHEELS_PYTEST) WHEELS_COMPARE=$(abspath $(PY)) tools/wheels/build_wheels.sh $(WHEEL_PYTHONS)

# The sdist builds a wheel as pip builds it on a user's machine (isolated,
# from a read-only unpacked tree) with the files of the checkout's wheel
# (tests/wheel/test_sdist.sh): a full build without ccache, the longest
# build of make test.
sdist-test: python-deps
	JOBS=$(JOBS) tests/wheel/test_sdist.sh $(BUILD) $(PY)

# The installed package (cmake --install into $(BUILD)/stage) and what is
# built against it: CMake and pkg-config consumers, shared and static; then
# every FFI: ctypes (standard library only), Rust, Go, and a real renderer.
STAGE := $(abspath $(BUILD))/stage
STAGE_PC := $(STAGE)/lib/pkgconfig

install-test: build
	tests/install/test_install.sh $(BUILD)

# mcstat vendored into a parent project by add_subdirectory and by FetchContent
# (tests/vendor): libraries only, no tests or install rules of its own, the
# parent's build type untouched.
vendor-test:
	tests/vendor/test_vendor.sh $(BUILD)

ctypes-test: install-test
	python3 examples/ctypes/test_ctypes.py $(STAGE)/lib/libmcstat.so

# Toolchains: the machine's (rustup's ~/.cargo/bin, /usr/local/go) when
# present, else Debian's cargo/rustc and golang-go (tools/deps-debian.sh rust go).
TOOL_PATH := $(HOME)/.cargo/bin:/usr/local/go/bin:$(PATH)
rust-deps:
	@export PATH="$(TOOL_PATH)"; command -v cargo > /dev/null || { echo "no cargo: tools/deps-debian.sh rust installs it"; exit 1; }

go-deps:
	@export PATH="$(TOOL_PATH)"; command -v go > /dev/null || { echo "no go: tools/deps-debian.sh go installs it"; exit 1; }

# Rust: against the staged libmcstat.so, then linked statically.  Neither
# run sets LD_LIBRARY_PATH: the build scripts record the library's directory
# as an rpath, and the static feature must not need the shared library.
rust-test: install-test rust-deps
	cd bindings/rust && PATH="$(TOOL_PATH)" PKG_CONFIG_PATH=$(STAGE_PC) \
	  env -u LD_LIBRARY_PATH cargo test --locked -j $(JOBS)
	cd bindings/rust && PATH="$(TOOL_PATH)" PKG_CONFIG_PATH=$(STAGE_PC) \
	  env -u LD_LIBRARY_PATH cargo test --locked -j $(JOBS) -p mcstat --features static

# Go: no LD_LIBRARY_PATH: the run path comes from mcstat-rpath.pc.
go-test: install-test go-deps
	cd bindings/go && PATH="$(TOOL_PATH)" PKG_CONFIG_PATH=$(STAGE_PC) \
	  go test -count=1 -v .

# The README's quickstarts (C, C++, Python, Rust, Go), built and run as a
# new user would, against the staged install (tests/quickstart).
quickstart-test: install-test python rust-deps go-deps
	PATH="$(TOOL_PATH)" python3 tests/quickstart/run_quickstarts.py --stage $(STAGE) \
	  --python $(PY) --cargo-target-dir $(BUILD)/quickstart-cargo

# Mitsuba 3 from PyPI (examples/mitsuba/requirements.txt).  Only when pip
# cannot install the wheel do the tests skip, and they say pip's reason.
# examples/mitsuba's tests include those of the package's own adapters,
# mcstat.mitsuba (test_shipped_adapters.py).
# The demo suite (examples/mitsuba/suite) runs under mcstat's pytest plugin
# at master seed 0, where every case passes, and again with one planted bug,
# where exactly the planted test must fail (a fixed-seed regression test;
# its calibration over seeds is examples/mitsuba/RESULTS_suite.md's).
SUITE_PLANT := bsdf-plastic-t20-p0=bsdf-pdf:1.05
mitsuba-test: install-test python
	@if $(PY) -m pip install -q -r examples/mitsuba/requirements.txt > $(BUILD)/mitsuba-pip.log 2>&1; then \
	  MCSTAT_LIBDIR=$(STAGE)/lib $(PY) -m pytest -q -p no:cacheprovider examples/mitsuba \
	    --ignore=examples/mitsuba/suite && \
	  $(PY) -m pytest -q -p no:cacheprovider examples/mitsuba/suite --mcstat-alpha 1e-2 --mcstat-seed 0 && \
	  { MCSTAT_DEMO_PLANT=$(SUITE_PLANT) $(PY) -m pytest -q -rf -p no:cacheprovider \
	      examples/mitsuba/suite/test_bsdfs.py --mcstat-alpha 1e-2 --mcstat-seed 0 > $(BUILD)/suite-planted.log; \
	    tail -4 $(BUILD)/suite-planted.log; \
	    test "$$(grep -c '^FAILED' $(BUILD)/suite-planted.log)" = 1 && \
	    grep -q '^FAILED.*\[$(firstword $(subst =, ,$(SUITE_PLANT)))\]' $(BUILD)/suite-planted.log || \
	    { echo "the planted suite should fail on $(SUITE_PLANT) alone"; exit 1; }; }; \
	else \
	  cat $(BUILD)/mitsuba-pip.log; \
	  MCSTAT_MITSUBA_UNAVAILABLE="$$(tail -1 $(BUILD)/mitsuba-pip.log)" MCSTAT_LIBDIR=$(STAGE)/lib \
	    $(PY) -m pytest -q -rs -p no:cacheprovider examples/mitsuba; \
	fi

# make test: first what it needs (Debian packages, then .venv), then each
# step of ci/test-steps.mk in order; the first failing step stops the run.
include ci/test-steps.mk
test:
	tools/deps-debian.sh test
	$(MAKE) python-deps
	$(MAKE) $(TEST_STEPS) CMAKE_FLAGS="$(CMAKE_FLAGS) -DMCSTAT_REQUIRE_TEST_FRAMEWORKS=ON"

# ---- API reference (make docs; part of make test) ----------------------------
# Into $(BUILD)/docs: c/html (Doxygen over mcstat.h, mcstat/*.h and mcstat_check.h,
# tools/docs/Doxyfile), python (Sphinx autodoc over the package installed in
# .venv, tools/docs/python), rust (rustdoc of bindings/rust; its build script
# finds the staged libmcstat) and go/mcstat.txt (go doc -all).  A warning of
# any of them fails: Doxygen's WARN_AS_ERROR, sphinx-build -W, RUSTDOCFLAGS=-D
# warnings, and doc comments gofmt would reformat.  Needs doxygen
# (tools/deps-debian.sh docs) and sphinx (requirements-dev.txt).
DOCS := $(abspath $(BUILD))/docs
docs: docs-c docs-python docs-rust docs-go

docs-c:
	rm -rf $(DOCS)/c && mkdir -p $(DOCS)/c
	MCSTAT_DOCS_OUT=$(DOCS)/c doxygen tools/docs/Doxyfile
	@echo "C API reference: $(DOCS)/c/html/index.html"

docs-python: python
	rm -rf $(DOCS)/python $(DOCS)/.doctrees-python
	$(PY) -m sphinx -W --keep-going -q -b html -d $(DOCS)/.doctrees-python tools/docs/python $(DOCS)/python
	@echo "Python API reference: $(DOCS)/python/index.html"

docs-rust: install-test rust-deps
	cd bindings/rust && PATH="$(TOOL_PATH)" PKG_CONFIG_PATH=$(STAGE_PC) RUSTDOCFLAGS="-D warnings" \
	  CARGO_TARGET_DIR=$(DOCS)/rust-target cargo doc --no-deps --locked -j $(JOBS)
	rm -rf $(DOCS)/rust && cp -r $(DOCS)/rust-target/doc $(DOCS)/rust
	@echo "Rust API reference: $(DOCS)/rust/mcstat/index.html"

docs-go: go-deps
	@cd bindings/go && unformatted=$$(PATH="$(TOOL_PATH)" gofmt -l .) && \
	  if [ -n "$$unformatted" ]; then echo "docs-go: gofmt would rewrite (doc comments included): $$unformatted"; exit 1; fi
	mkdir -p $(DOCS)/go
	cd bindings/go && PATH="$(TOOL_PATH)" go doc -all . > $(DOCS)/go/mcstat.txt
	@echo "Go API reference: $(DOCS)/go/mcstat.txt"

# ---- ABI (part of make test) -------------------------------------------------
# The shared library built with debug information (Release flags plus -g) in
# $(BUILD)-abi, its ABI compared by abidiff with that of every release of
# this SOVERSION (libmcstat/abi/README.md; MCSTAT_SOVERSION in mcstat.h
# names the files): any change other than an addition fails.
MCSTAT_SOVERSION := $(shell sed -n 's/^\#define MCSTAT_SOVERSION \([0-9]*\)$$/\1/p' libmcstat/include/mcstat/version.h)
ABI_BASELINES := $(sort $(wildcard libmcstat/abi/libmcstat.so.$(MCSTAT_SOVERSION).*.abi))
abi-check:
	@[ -n "$(ABI_BASELINES)" ] || { echo "abi-check: no baseline for SOVERSION $(MCSTAT_SOVERSION) in libmcstat/abi"; exit 1; }
	cmake -S . -B $(BUILD)-abi -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-g \
	  -DMCSTAT_BUILD_TESTS=OFF -DMCSTAT_BUILD_EXAMPLES=OFF -DMCSTAT_BUILD_ESTIMATORS=OFF
	cmake --build $(BUILD)-abi -j $(JOBS) --target mcstat
	for base in $(ABI_BASELINES); do \
	  libmcstat/abi/check.sh $$base $(BUILD)-abi/libmcstat/libmcstat.so libmcstat/include || exit 1; \
	done

# ---- sanitizers and valgrind (part of make test) ---------------------------
# asan-test: every C test of libmcstat and libmcest, built with AddressSanitizer
#   and UndefinedBehaviorSanitizer (MCSTAT_SANITIZE in CMakeLists.txt says which
#   checks), in $(BUILD)-asan; the first error stops the test and the run.
# tsan-test: the multithreaded tests under ThreadSanitizer, in $(BUILD)-tsan.
# valgrind-test: memcheck over every ctest test of the normal build
#   (tests/valgrind/memcheck.py); errors and definite leaks fail.
# SAN_SIZE shrinks the slowest tests under these runs (they do the same work
# on smaller sizes; see each test's header).  Their costs, sanitizer builds
# included: bench/RESULTS_gate.md.
SAN_SIZE := MCSTAT_TEST_SCALE=20 MCSTAT_TEST_THREADS=3 MCSTAT_TEST_THREADS_REPS=1
SAN_CMAKE := -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMCSTAT_BUILD_EXAMPLES=ON
ASAN_ENV := ASAN_OPTIONS=halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=1:check_initialization_order=1:strict_init_order=1 \
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
TSAN_ENV := TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
# the tests that run threads: their own, or mcstat_ks_test_2's simulation threads
TSAN_TESTS := test_threads|test_ks$$|test_ks_calibration|test_stream|test_irradiance_mc|integrator_

asan-test:
	cmake -S . -B $(BUILD)-asan $(SAN_CMAKE) -DMCSTAT_SANITIZE=address,undefined
	cmake --build $(BUILD)-asan -j $(JOBS)
	$(ASAN_ENV) $(SAN_SIZE) ctest --test-dir $(BUILD)-asan --output-on-failure --stop-on-failure -j $(JOBS)

tsan-test:
	cmake -S . -B $(BUILD)-tsan $(SAN_CMAKE) -DMCSTAT_SANITIZE=thread
	cmake --build $(BUILD)-tsan -j $(JOBS)
	$(TSAN_ENV) $(SAN_SIZE) ctest --test-dir $(BUILD)-tsan --output-on-failure --stop-on-failure -j $(JOBS) \
	  -R '$(TSAN_TESTS)'

# Left out of valgrind-test (they run under asan-test): libmcest's test_brdf,
# test_radiance and test_sampler_gof, several minutes each under memcheck,
# whose statistical assertions need their full sample sizes (measured for
# test_brdf: at 1/10 of them, power and z checks fail).
VALGRIND_EXCLUDE := test_brdf|test_radiance|test_sampler_gof
valgrind-test: build
	$(SAN_SIZE) python3 tests/valgrind/memcheck.py $(BUILD) -j $(JOBS) -E '$(VALGRIND_EXCLUDE)'

# portability-test: no result may depend on the width of long double or on
# the caller's floating-point environment, and -ffast-math is refused:
#   (a) libmcstat, libmcest and the C tests built with -mlong-double-64 (the
#       64-bit long double of MSVC and arm64 macOS; x86-64 only) in
#       $(BUILD)-ld64, and their ctest, which includes
#   (b) fast_math_refused: libmcstat does not compile with -ffast-math;
#   (c) the ctest suite of $(BUILD) in processes that start with
#       flush-to-zero and denormals-are-zero set (tests/ftz/ftz_daz.c through
#       LD_PRELOAD; test_fpenv checks that the mode is really on).
# SAN_SIZE shrinks test_bad_input and test_threads as for the sanitizers; left
# out, as from valgrind-test, libmcest's statistical tests (test_brdf,
# test_radiance, test_sampler_gof: minutes at the full size their
# assertions need; nothing in them depends on long double, and they passed
# under FTZ/DAZ when this target was written).  Its cost:
# bench/RESULTS_gate.md.
PORT_EXCLUDE := test_brdf|test_radiance|test_sampler_gof
portability-test: build
	@if [ "$$(uname -m)" = x86_64 ]; then \
	  cmake -S . -B $(BUILD)-ld64 -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-mlong-double-64 && \
	  cmake --build $(BUILD)-ld64 -j $(JOBS) && \
	  $(SAN_SIZE) ctest --test-dir $(BUILD)-ld64 --output-on-failure -j $(JOBS) -E '$(PORT_EXCLUDE)'; \
	else \
	  echo "portability-test: -mlong-double-64 is an x86-64 option; $$(uname -m) skips (a), runs fast_math_refused"; \
	  ctest --test-dir $(BUILD) --output-on-failure -R fast_math_refused; \
	fi
	$(SAN_SIZE) MCSTAT_EXPECT_FTZ=1 LD_PRELOAD=$(abspath $(BUILD))/tests/c/libmcstat_ftz_daz.so \
	  ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -E '$(PORT_EXCLUDE)|fast_math_refused'

# The main job: the paper's case studies and the studies beyond it on its scene (full budgets, about
# a minute on 2 cores), into $(REPORT)/.
REPORT ?= report
demo:
	tools/deps-debian.sh demo
	$(MAKE) python
	$(VENV)/bin/mcstat reproduce --out $(REPORT)

# The same with the reduced budgets that CI uses.
demo-quick: python
	$(VENV)/bin/mcstat reproduce --quick --out $(REPORT)

# The C library's own demo: the five tests on generated estimates.
demo-c: build
	$(BUILD)/examples/c/mcstat_demo

bench: python
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_BENCH=ON -DMCSTAT_BUILD_TESTS=OFF
	cmake --build $(BUILD)-bench -j $(JOBS)
	$(PY) bench/run.py --build $(BUILD)-bench

# Cost per sample of an embedded check (mcstat_stream); see bench/RESULTS_check.md.
bench-check:
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_BENCH=ON -DMCSTAT_BUILD_TESTS=OFF
	cmake --build $(BUILD)-bench -j $(JOBS) --target bench_check
	$(BUILD)-bench/bench/bench_check

bench-python: python
	$(PY) bench/bench_python.py

# Power of the renderer checks against the Neyman-Pearson oracle and the chi2
# tests of Mitsuba 3 and pbrt-v4 (n90 per planted bug, one core, about
# 11 minutes); rewrites bench/RESULTS_power.md above its diagnosis.
bench-power: python
	$(PY) bench/bench_power.py --write

# C estimators against their NumPy twins; rewrites bench/RESULTS_estimators.md.
bench-estimators: python-deps
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_BENCH=ON -DMCSTAT_BUILD_TESTS=OFF
	cmake --build $(BUILD)-bench -j $(JOBS) --target bench_estimators
	$(PY) bench/bench_estimators_numpy.py --c $(BUILD)-bench/bench/bench_estimators --write

# Regenerates every committed reference number (tests/data/, and the
# library's log_gammastar_cheb.h) with the generators of tools/refgen/, in
# dependency order (tools/refgen/run.py --list shows it); the accuracy table
# is re-measured on its committed cases (REFGEN_FLAGS=--accuracy-refs draws
# new ones).  Needs R (tools/deps-debian.sh references); no test needs this run.
REFGEN_FLAGS ?=
references: build python-deps
	$(PY) tools/refgen/run.py --python $(PY) --lib $(BUILD)/libmcstat/libmcstat.so --build $(BUILD) $(REFGEN_FLAGS)

# The accuracy table libmcstat/ACCURACY.md and tests/data/accuracy.tsv (the
# bounds test_accuracy and test_reference enforce): the built library against
# 50-digit mpmath references, through ctypes (no R).  accuracy re-measures on
# the committed cases (seconds); accuracy-refs draws the cases and recomputes
# their references first (about 2 minutes on 2 cores).  Either refuses to
# loosen a committed bound unless ACCURACY_FLAGS=--accept-looser.
ACCURACY_FLAGS ?=
accuracy: build python-deps
	$(PY) tools/refgen/make_accuracy.py --lib $(BUILD)/libmcstat/libmcstat.so $(ACCURACY_FLAGS)

accuracy-refs: build python-deps
	$(PY) tools/refgen/make_accuracy.py --lib $(BUILD)/libmcstat/libmcstat.so --refs $(ACCURACY_FLAGS)

# ---- fuzzing (tests/fuzz/README.md) -------------------------------------------
# libFuzzer harnesses built by clang with ASan + UBSan in $(BUILD)-fuzz; each
# runs FUZZ_SECONDS, two at a time; any crash, sanitizer report or invariant
# violation fails.  fuzz-replay only re-runs the committed corpus and
# regressions (a few seconds; ctest does the same in every build).
FUZZ_SECONDS ?= 60
FUZZ_BUILD := $(BUILD)-fuzz
fuzz-build:
	CC=clang cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMCSTAT_FUZZ=ON \
	  -DMCSTAT_BUILD_TESTS=OFF -DMCSTAT_BUILD_EXAMPLES=OFF -DMCSTAT_BUILD_ESTIMATORS=OFF
	cmake --build $(FUZZ_BUILD) -j $(JOBS)

fuzz-replay: fuzz-build
	ctest --test-dir $(FUZZ_BUILD) --output-on-failure -j $(JOBS)

fuzz: fuzz-replay
	tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) 2

# Mutation fuzzing explores: two runs of the same commit differ, so it is
# never part of the gate.  `make test` runs fuzz-replay (every committed
# corpus and regression input under clang's ASan + UBSan: the same verdict
# every time) and fuzz-report, a short exploration whose findings are written
# to $(FUZZ_BUILD)/fuzz/REPORT.md and printed, and which never fails the run.
# Exploration at length is `make fuzz`, which fails on a finding.
FUZZ_REPORT_SECONDS ?= 20
fuzz-report: fuzz-build
	FUZZ_REPORT=$(abspath $(FUZZ_BUILD))/fuzz/REPORT.md tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_REPORT_SECONDS) 2

clean:
	rm -rf $(BUILD) $(BUILD)-bench $(BUILD)-fuzz
	rm -rf $(BUILD)-asan $(BUILD)-tsan $(BUILD)-abi $(BUILD)-ld64
