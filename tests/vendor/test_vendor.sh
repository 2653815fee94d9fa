#!/usr/bin/env bash
# mcstat vendored into a parent project (tests/vendor/parent), twice: by
# add_subdirectory of this checkout, and by FetchContent from an archive of
# it (URL, no network).  Each time the parent builds and runs its consumer
# against mcstat::mcstat and mcstat::mcstat_static, and:
#   - ctest -N lists the parent's two tests and none of mcstat's;
#   - it configures without a CMake warning;
#   - the parent's CMAKE_BUILD_TYPE is what the parent gave (empty stays empty);
#   - no target of mcstat's tests, fuzz drivers, examples, benchmarks or libmcest exists;
#   - cmake --install of the parent installs its own files only, and mcstat's
#     too once MCSTAT_INSTALL=ON.
# usage: tests/vendor/test_vendor.sh BUILD_DIR   (work in BUILD_DIR/vendor-test)
set -euo pipefail
cd "$(dirname "$0")/../.."
src=$(pwd)
mkdir -p "${1:-build}"
work="$(cd "${1:-build}" && pwd)/vendor-test"
rm -rf "$work"
mkdir -p "$work"
fail() { echo "vendor test FAILED: $*" >&2; exit 1; }

# The archive FetchContent downloads: the checkout's files (tracked, and new
# ones not ignored), under one top directory as a release tarball has them.
if git rev-parse --is-inside-work-tree > /dev/null 2>&1; then
    git ls-files -z -co --exclude-standard | while IFS= read -r -d '' f; do [ -f "$f" ] && printf '%s\0' "$f"; done \
        | tar -czf "$work/mcstat-src.tar.gz" --null -T - --transform 's,^,mcstat/,'
else
    tar -czf "$work/mcstat-src.tar.gz" --exclude='./build*' --exclude=./.venv --exclude=./.git \
        --transform 's,^\.,mcstat,' .
fi

# the targets mcstat may add to a parent: its libraries, nothing else
allowed_mcstat_targets="mcstat mcstat_static mcstat_objects"

check_parent() { # mode build_dir expected_build_type
    local mode=$1 b=$2 want_type=$3
    local got_type
    got_type=$(sed -n 's/^CMAKE_BUILD_TYPE:[A-Z]*=//p' "$b/CMakeCache.txt")
    [ "$got_type" = "$want_type" ] || fail "$mode: the parent's CMAKE_BUILD_TYPE is '$got_type', it gave '$want_type'"

    cmake --build "$b" -j 2 > "$b.build.log" 2>&1 || { cat "$b.build.log"; fail "$mode: build"; }

    local listed
    listed=$(ctest --test-dir "$b" -N | sed -n 's/^ *Test *#[0-9]*: //p' | sort | paste -sd' ')
    [ "$listed" = "parent_consumer parent_consumer_static" ] || fail "$mode: ctest -N lists: $listed"
    ctest --test-dir "$b" --output-on-failure > "$b.ctest.log" 2>&1 || { cat "$b.ctest.log"; fail "$mode: consumers"; }

    # every target of the build (Makefile generator's help), less CMake's own
    # and the parent's: what is left must be mcstat's libraries
    local t extra=""
    for t in $(cmake --build "$b" --target help | sed -n 's/^\.\.\. \([^ ]*\).*/\1/p'); do
        case "$t" in
            all | clean | depend | edit_cache | rebuild_cache | install | install/* | list_install_components | test) ;;
            consumer | consumer_static | *.o | *.i | *.s) ;;
            *) [[ " $allowed_mcstat_targets " == *" $t "* ]] || extra+=" $t" ;;
        esac
    done
    [ -z "$extra" ] || fail "$mode: targets beyond mcstat's libraries:$extra"

    rm -rf "$b.stage"
    cmake --install "$b" --prefix "$b.stage" > /dev/null
    local files
    files=$(cd "$b.stage" && find . -type f -o -type l | sort | paste -sd' ')
    [ "$files" = "./bin/consumer ./bin/consumer_static" ] || fail "$mode: the parent's install holds: $files"
    echo "vendor test: $mode: builds and runs, 2 parent tests, build type '$want_type' kept, libraries only, nothing of mcstat installed"
}

configure() { # build_dir args...
    local b=$1
    shift
    cmake -G "Unix Makefiles" -S tests/vendor/parent -B "$b" "$@" > "$b.configure.log" 2>&1 \
        || { cat "$b.configure.log"; fail "configure $b"; }
    if grep -q "CMake .*Warning" "$b.configure.log"; then cat "$b.configure.log"; fail "configure $b: CMake warnings"; fi
}

# 1. add_subdirectory, no build type given
configure "$work/subdir" -DMCSTAT_VENDOR=subdir -DMCSTAT_SOURCE_DIR="$src"
check_parent add_subdirectory "$work/subdir" ""

# 2. FetchContent from the archive, the parent's own build type
configure "$work/fetch" -DMCSTAT_VENDOR=fetch -DMCSTAT_URL="$work/mcstat-src.tar.gz" -DCMAKE_BUILD_TYPE=RelWithDebInfo
check_parent FetchContent "$work/fetch" RelWithDebInfo

# 3. MCSTAT_INSTALL=ON: the parent's install carries libmcstat's
configure "$work/subdir" -DMCSTAT_INSTALL=ON
cmake --build "$work/subdir" -j 2 > /dev/null
rm -rf "$work/stage-on"
cmake --install "$work/subdir" --prefix "$work/stage-on" > /dev/null
for f in bin/consumer include/mcstat.h include/mcstat/tests.h include/mcstat/embedded.h include/mcstat_check.h lib/cmake/mcstat/mcstatConfig.cmake \
         lib/cmake/mcstat/mcstatTargets.cmake lib/pkgconfig/mcstat.pc lib/libmcstat.a; do
    [ -e "$work/stage-on/$f" ] || [ -e "$work/stage-on/${f/lib\//lib64/}" ] || fail "MCSTAT_INSTALL=ON: $f not installed"
done
ls "$work"/stage-on/lib*/libmcstat.so.* > /dev/null 2>&1 || fail "MCSTAT_INSTALL=ON: no libmcstat.so"
echo "vendor test: MCSTAT_INSTALL=ON: the parent's install carries libmcstat's headers, libraries and packages"
echo "1 passed, 0 failed"
