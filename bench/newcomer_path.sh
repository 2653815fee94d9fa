#!/usr/bin/env bash
# A newcomer's path: README.md from the top to a passing C, Python and Rust
# quickstart, with the README's own commands, timed per step.  A fresh
# clone and an empty HOME (so an empty pip cache: numpy, SciPy and the build
# tools come from PyPI); Debian's packages and the Rust toolchain are the
# machine's.  Writes bench/RESULTS_newcomer.md.  Not part of make test.
#   usage: bench/newcomer_path.sh [WORKDIR]
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-/tmp/mcstat-newcomer}
rm -rf "$work"
mkdir -p "$work/home"
cargo_bin=$(dirname "$(command -v cargo)")
export CARGO_HOME=${CARGO_HOME:-$HOME/.cargo} RUSTUP_HOME=${RUSTUP_HOME:-$HOME/.rustup}
export HOME="$work/home" PATH="$cargo_bin:$PATH"
rows=()
t0=$SECONDS last=$SECONDS
step() { rows+=("| $1 | $((SECONDS - last)) |"); last=$SECONDS; }
ok() { grep -q "decision at alpha = 0.05: equal" "$1" && grep -q "decision at alpha = 0.05: less" "$1"; }

git clone -q "$repo" "$work/src"
cd "$work/src"
step "git clone" 
tools/deps-debian.sh build > "$work/deps.log" 2>&1
step "tools/deps-debian.sh build (packages already there)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DMCSTAT_BUILD_TESTS=OFF > "$work/cmake.log"
cmake --build build -j > "$work/build.log"
cmake --install build --prefix "$HOME/.local" > "$work/install.log"
export PKG_CONFIG_PATH="$HOME/.local/lib/pkgconfig" CMAKE_PREFIX_PATH="$HOME/.local"
step "cmake configure, build, install"
# the quickstarts as a reader copies them out of README.md (the blocks
# make quickstart-test reads)
python3 - "$work" <<'PY'
import pathlib, sys
sys.path.insert(0, "tests/quickstart")
from run_quickstarts import blocks
for name, body in blocks().items():
    pathlib.Path(sys.argv[1], f"qs-{name}").write_text(body)
PY
mkdir -p "$work/c" && cd "$work/c" && cp "$work/qs-c" quickstart.c
cc quickstart.c $(pkg-config --cflags --libs mcstat-rpath) -lm && ./a.out > out.txt && ok out.txt
step "C quickstart: compile and run"
cd "$work/src"
tools/deps-debian.sh python > "$work/deps-py.log" 2>&1
python3 -m venv "$work/venv"
"$work/venv/bin/pip" install -q . > "$work/pip.log" 2>&1
step "python3 -m venv, pip install . (from PyPI: build tools, numpy, SciPy)"
mkdir -p "$work/py" && cd "$work/py" && cp "$work/qs-python" quickstart.py
"$work/venv/bin/python" quickstart.py > out.txt && ok out.txt
step "Python quickstart"
mkdir -p "$work/rs/src" && cd "$work/rs" && cp "$work/qs-rust-toml" Cargo.toml && cp "$work/qs-rust" src/main.rs
cargo run -q > out.txt 2> "$work/cargo.log" && ok out.txt
step "Rust quickstart: cargo run (builds the crates)"
total=$((SECONDS - t0))
{
    echo "# A newcomer's path: README to passing C, Python and Rust quickstarts"
    echo
    echo "\`bench/newcomer_path.sh\` on $(date -u +%Y-%m-%d), $(nproc) cores, commit $(git -C "$repo" rev-parse --short HEAD):"
    echo "a fresh clone, an empty HOME and pip cache; Debian's packages (the"
    echo "\`apt-get\` of \`tools/deps-debian.sh\`) and the Rust toolchain were already installed,"
    echo "so a machine without them adds their download and install."
    echo
    echo "| step | seconds |"
    echo "|---|---:|"
    printf '%s\n' "${rows[@]}"
    echo "| **total** | **$total** |"
} > "$repo/bench/RESULTS_newcomer.md"
cat "$repo/bench/RESULTS_newcomer.md"
