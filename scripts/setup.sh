#!/usr/bin/env bash
# Project set-up, idempotent (a few seconds when already done):
#  1. a project-local Python virtual environment .venv with torch==2.13.0 from PyPI, whose
#     bundled libtorch is the one tch 0.26 links against (CUDA build: the same binary uses a
#     GPU when one is present), and numpy (for the tests that load our .npy files as a Python
#     user would, and for the PyTorch reference benchmark);
#  2. .cargo/config.toml pointing LIBTORCH at it, so plain `cargo build` / `cargo test` work;
#  3. the ffmpeg command-line tools (Debian's `ffmpeg` package) for `estimate` on recordings,
#     where this machine lets us install them (root or password-less sudo with apt-get);
#     otherwise a note, and the tests that need them skip.
set -euo pipefail
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

if ! command -v ffmpeg >/dev/null 2>&1 || ! command -v ffprobe >/dev/null 2>&1; then
    sudo=""
    [ "$(id -u)" = 0 ] || { sudo -n true 2>/dev/null && sudo="sudo -n"; } || sudo="none"
    if [ "$sudo" != "none" ] && command -v apt-get >/dev/null 2>&1; then
        echo "setup: installing ffmpeg with apt-get (for estimate on videos)" >&2
        $sudo apt-get update -qq >/dev/null 2>&1 || true
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq ffmpeg >/dev/null 2>&1 ||
            echo "setup: apt-get could not install ffmpeg; videos need it (tests skip)" >&2
    else
        echo "setup: ffmpeg not found and not installable here; install it to read videos (tests skip)" >&2
    fi
fi
