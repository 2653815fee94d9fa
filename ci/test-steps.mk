# What `make test` runs, in this order (the Makefile's test target runs
# tools/deps-debian.sh test and fills .venv first).  Each step is a Makefile
# target, runnable alone; the first that fails stops the run.  A new kind of
# check becomes a target in the Makefile and a line here.

# the C tests of libmcstat and libmcest (tests/c, estimators/tests), ctest
TEST_STEPS := ctest
# every exported function reached by every binding or exempted with a reason
# (tests/bindings/check_coverage.py, tests/bindings/coverage_exempt.txt)
TEST_STEPS += binding-coverage
# the Python package built into .venv, and its tests (tests/python)
TEST_STEPS += pytest
# the binary wheel: repaired by auditwheel (manylinux, GSL and libRmath
# bundled), installed into a bare venv with its extras and run (tests/wheel)
TEST_STEPS += wheel-test
# one more CPython (3.13 from pyenv): its wheel, built and repaired the same
# way, in a bare venv of that interpreter (tests/wheel/test_wheel_extra.sh)
TEST_STEPS += wheel-test-extra
# the sdist builds, isolated and read-only, the checkout's wheel (tests/wheel;
# a full build without ccache; each step's cost: bench/RESULTS_gate.md)
TEST_STEPS += sdist-test
# cmake --install into build/stage, and CMake and pkg-config consumers of it,
# shared and static (tests/install)
TEST_STEPS += install-test
# mcstat vendored by a parent project: add_subdirectory and FetchContent (tests/vendor)
TEST_STEPS += vendor-test
# the installed library through ctypes (examples/ctypes)
TEST_STEPS += ctypes-test
# the Rust and Go bindings against the installed library (bindings/rust, bindings/go)
TEST_STEPS += rust-test go-test
# the README's quickstarts, built and run as a new user would (tests/quickstart)
TEST_STEPS += quickstart-test
# a real renderer, Mitsuba 3 from PyPI (examples/mitsuba)
TEST_STEPS += mitsuba-test
# the shared library's ABI against the baseline of its SOVERSION (libmcstat/abi)
TEST_STEPS += abi-check
# the API reference of C, Python, Rust and Go into build/docs, warnings as errors (make docs)
TEST_STEPS += docs
# every C test under ASan + UBSan, the threaded ones under TSan, memcheck
TEST_STEPS += asan-test tsan-test valgrind-test
# 64-bit long double, -ffast-math refused, flush-to-zero callers (tests/ftz)
TEST_STEPS += portability-test
# the committed fuzz corpus and regressions under clang's sanitizers, then a
# short exploration that reports and never fails (tests/fuzz)
TEST_STEPS += fuzz-replay fuzz-report
