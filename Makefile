# The two commands of the README, on a fresh Debian machine:
#   make demo   runs the main job
#   make test   builds everything and passes the tests
# Each first installs what it needs: Debian packages through apt-get (only
# those missing), Python packages through pip into ./.venv.

SHELL := /bin/bash
BUILD ?= build
VENV ?= .venv
PY := $(VENV)/bin/python
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
APT_PACKAGES := libgsl-dev cmake pkg-config build-essential python3-venv python3-dev
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all deps system-deps python-deps build test ctest python pytest install-test ctypes-test demo bench bench-check bench-python bench-estimators references clean

all: build

# ---- dependencies ----------------------------------------------------------
system-deps:
	@missing=""; for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

$(VENV)/.installed: requirements-dev.txt
	python3 -m venv $(VENV)
	$(PY) -m pip install -q --upgrade pip
	$(PY) -m pip install -q -r requirements-dev.txt
	touch $@

python-deps: $(VENV)/.installed

deps: system-deps python-deps

# ---- build, test, demo -------------------------------------------------------
build: system-deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)
	cmake --build $(BUILD) -j $(JOBS)

ctest: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# The Python package, built by scikit-build-core through the same CMake
# (build/python/), installed into .venv.
python: system-deps python-deps
	CMAKE_BUILD_PARALLEL_LEVEL=$(JOBS) $(PY) -m pip install -q --no-build-isolation .

pytest: python
	$(PY) -m pytest -q tests/python

# The installed package (cmake --install into $(BUILD)/stage) and what is
# built against it: CMake and pkg-config consumers, shared and static; then
# every FFI: ctypes (standard library only), Rust, Go, and a real renderer.
STAGE := $(abspath $(BUILD))/stage
STAGE_PC := $(STAGE)/lib/pkgconfig

install-test: build
	tests/install/test_install.sh $(BUILD)

ctypes-test: install-test
	python3 examples/ctypes/test_ctypes.py $(STAGE)/lib/libmcstat.so

test: deps ctest pytest install-test ctypes-test

demo: build
	$(BUILD)/examples/c/mcstat_demo

bench: deps
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_BENCH=ON -DMCSTAT_BUILD_TESTS=OFF
	cmake --build $(BUILD)-bench -j $(JOBS)
	$(PY) bench/run.py --build $(BUILD)-bench

# Cost per sample of an embedded check (mcstat_stream); see bench/RESULTS_check.md.
bench-check: system-deps
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_BENCH=ON -DMCSTAT_BUILD_TESTS=OFF
	cmake --build $(BUILD)-bench -j $(JOBS) --target bench_check
	$(BUILD)-bench/bench/bench_check

bench-python: python
	$(PY) bench/bench_python.py

# C estimators against their NumPy twins; rewrites bench/RESULTS_estimators.md.
bench-estimators: python-deps
	cmake -S . -B $(BUILD)-bench -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_BENCH=ON -DMCSTAT_BUILD_TESTS=OFF
	cmake --build $(BUILD)-bench -j $(JOBS) --target bench_estimators
	$(PY) bench/bench_estimators_numpy.py --c $(BUILD)-bench/bench/bench_estimators --write

# Regenerates the committed reference numbers (needs R for the formatting).
references: python-deps
	$(PY) tests/reference/make_reference.py
	Rscript tests/reference/make_rformat.R
	Rscript tests/reference/make_rblocks_python.R

clean:
	rm -rf $(BUILD) $(BUILD)-bench
