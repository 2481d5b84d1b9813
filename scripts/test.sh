#!/usr/bin/env bash
# Every check, as README.md's second command and CI run it: set-up (idempotent, with the browser
# the report test needs), formatting, the layout's invariants (no import cycles, files of at most
# 350 lines, no #[path] test files), clippy with warnings as errors, then all unit and end-to-end
# tests (CPU only; the CUDA test needs `--features physvid-estimator/cuda-tests` on a GPU
# machine), then the Python package built and its pytest tests.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/setup.sh --tests
cargo fmt --all -- --check
scripts/check_layout.sh
# Release profile throughout, so the libtorch bindings are compiled once for clippy and tests.
cargo clippy --release --workspace --all-targets -- -D warnings
cargo test --release --workspace
# The Python package (python/, maturin): built into .venv, then its pytest tests, which compare
# it with the binaries just built.
PATH="$root/.venv/bin:$PATH" .venv/bin/python -m pip install --quiet --disable-pip-version-check \
    --no-build-isolation ./python
.venv/bin/python -m pytest -q python/tests
