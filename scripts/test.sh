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
# The Python package (python/, maturin): its wheel built once (on the libtorch just compiled),
# installed into .venv, then its pytest tests, which compare it with the binaries just built and
# install the same wheel into a fresh venv.
rm -rf target/wheels
PATH="$root/.venv/bin:$PATH" .venv/bin/maturin build --quiet --release -m python/Cargo.toml \
    --auditwheel skip -o target/wheels
wheel="$(ls target/wheels/physvid-*.whl)"
.venv/bin/python -m pip install --quiet --disable-pip-version-check --no-deps --force-reinstall \
    "$wheel"
PHYSVID_WHEEL="$root/$wheel" .venv/bin/python -m pytest -q python/tests
