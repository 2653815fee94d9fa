#!/bin/sh
# compile_clean.sh COMPILER FLAGS... : runs the compiler on a header's test
# file (testing_pbrt_header_warnings).  A script rather than the compiler
# itself as ctest's command, so that tests/valgrind/memcheck.py, which
# memory-checks the ELF commands, leaves the compiler's own leaks alone.
exec "$@"
