#!/usr/bin/env bash
# Project set-up, idempotent (a few seconds when already done):
#  1. a project-local Python virtual environment .venv with torch==2.13.0 from PyPI, whose
#     bundled libtorch is the one tch 0.26 links against (CUDA build: the same binary uses a
#     GPU when one is present), and numpy (for the tests that load our .npy files as a Python
#     user would, and for the PyTorch reference benchmark);
#  2. .cargo/config.toml pointing LIBTORCH at it, so plain `cargo build` / `cargo test` work;
#  3. the ffmpeg command-line tools (Debian's `ffmpeg` package) for `estimate` on recordings,
#     where this machine lets us install them (root or password-less sudo with apt-get);
#     otherwise a note, and the tests that need them skip;
#  4. with --tests (what scripts/test.sh passes), Debian's `chromium` the same way, for the test
#     that opens report.html in a browser, and `slurmctld`, `slurmd` and `slurm-client`, for the
#     test that runs a batch as a job array on a one-node cluster (scripts/slurm.sh): the main
#     job needs neither; and maturin, pytest and matplotlib in .venv, for the Python package and
#     its tests.
set -euo pipefail
for_tests=""
case "${1:-}" in
    --tests) for_tests=1 ;;
    "") ;;
    *) echo "setup: unknown argument '$1' (use: scripts/setup.sh [--tests])" >&2; exit 2 ;;
esac
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
TORCH_VERSION="2.13.0"
PYTHON="${PYTHON:-python3}"

torch_dir() {
    .venv/bin/python -c 'import os, torch; print(os.path.dirname(torch.__file__))' 2>/dev/null
}

have_torch() {
    [ -x .venv/bin/python ] &&
        [ "$(.venv/bin/python -c 'import numpy, torch; print(torch.__version__.split("+")[0])' 2>/dev/null)" = "$TORCH_VERSION" ]
}

if ! have_torch; then
    echo "setup: installing torch==$TORCH_VERSION into .venv (about 4.7 GB, a minute or two)" >&2
    [ -x .venv/bin/python ] || "$PYTHON" -m venv .venv
    .venv/bin/python -m pip install --quiet --disable-pip-version-check "torch==$TORCH_VERSION" numpy
    have_torch || { echo "setup: torch $TORCH_VERSION did not install into .venv" >&2; exit 1; }
fi

# The Python package (python/) is built with maturin and tested with pytest (and its figures
# with matplotlib), all in .venv, so that the test command itself downloads nothing.
if [ -n "$for_tests" ] && ! .venv/bin/python -c 'import pytest, maturin, matplotlib' 2>/dev/null; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check pytest "maturin>=1.8,<2" \
        matplotlib
fi

libtorch="$(torch_dir)"
[ -f "$libtorch/lib/libtorch.so" ] || [ -f "$libtorch/lib/libtorch_cpu.so" ] || {
    echo "setup: no libtorch shared libraries under $libtorch/lib" >&2
    exit 1
}
mkdir -p .cargo
config=$(cat <<TOML
# Written by scripts/setup.sh; do not edit (it is regenerated).
[env]
LIBTORCH = "$libtorch"
TOML
)
if [ "$(cat .cargo/config.toml 2>/dev/null)" != "$config" ]; then
    printf '%s\n' "$config" > .cargo/config.toml
    echo "setup: wrote .cargo/config.toml (LIBTORCH=$libtorch)" >&2
fi

# apt_install PACKAGE WHY: installs a Debian package where this machine lets us (root or
# password-less sudo with apt-get); otherwise a note (the tests that need it skip).
apt_updated=""
apt_install() {
    local sudo=""
    [ "$(id -u)" = 0 ] || { sudo -n true 2>/dev/null && sudo="sudo -n"; } || sudo="none"
    if [ "$sudo" != "none" ] && command -v apt-get >/dev/null 2>&1; then
        echo "setup: installing $1 with apt-get ($2)" >&2
        [ -n "$apt_updated" ] || { $sudo apt-get update -qq >/dev/null 2>&1 || true; apt_updated=1; }
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "$1" >/dev/null 2>&1 ||
            echo "setup: apt-get could not install $1 ($2; tests skip)" >&2
    else
        echo "setup: $1 not found and not installable here ($2; tests skip)" >&2
    fi
}

if ! command -v ffmpeg >/dev/null 2>&1 || ! command -v ffprobe >/dev/null 2>&1; then
    apt_install ffmpeg "for estimate on videos"
fi
if [ -n "$for_tests" ] && ! command -v chromium >/dev/null 2>&1; then
    apt_install chromium "for the test that opens report.html in a headless browser"
fi
if [ -n "$for_tests" ]; then
    for daemon in slurmctld slurmd sbatch; do
        if ! command -v "$daemon" >/dev/null 2>&1; then
            package="$daemon"
            [ "$daemon" = sbatch ] && package=slurm-client
            apt_install "$package" "for the test that runs a batch as a Slurm job array"
        fi
    done
fi
