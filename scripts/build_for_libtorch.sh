#!/usr/bin/env bash
# Builds gen, estimate and the CUDA test against another libtorch than tch expects, for a GPU
# machine whose PyTorch is another version and which has no Rust (how the GPU figures in
# docs/results/gpu.md were made: torch 2.11 there, tch 0.26 expects 2.13).
#   scripts/build_for_libtorch.sh TORCH_DIR OUT_DIR
# TORCH_DIR: a `torch` folder (include/, lib/) of the same version as the target machine's, e.g.
# unpacked from that version's wheel (`pip download --no-deps torch==2.11.0`, then unzip). The
# wrapper that tch generates names a few operators an older libtorch lacks; their functions are
# replaced by ones that raise "not in this libtorch" (nothing here calls them). OUT_DIR gets the
# stripped binaries; on the target run them with LD_LIBRARY_PATH set to its torch/lib, and the
# CUDA test from the estimator folder with the binaries at the path the build used (printed).
set -euo pipefail
torch=$(cd "$1" && pwd); out=$(mkdir -p "$2" && cd "$2" && pwd)
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work=$(mktemp -d)
src=$(ls -d "${CARGO_HOME:-$HOME/.cargo}"/registry/src/*/torch-sys-"$(grep -A1 'name = "torch-sys"' "$root/Cargo.lock" | sed -n 's/version = "\(.*\)"/\1/p')" | head -1)
cp -r "$src" "$work/torch-sys"
# A copy of the workspace, so that the [patch] and its lock never touch the checkout.
mkdir -p "$work/ws" && (cd "$root" && git ls-files -z -co --exclude-standard | xargs -0 -I{} cp --parents {} "$work/ws/")
printf '\n[patch.crates-io]\ntorch-sys = { path = "%s" }\n' "$work/torch-sys" >> "$work/ws/Cargo.toml"
export LIBTORCH="$torch" LIBTORCH_BYPASS_VERSION_CHECK=1
target="$out/target"
build() {
  (cd "$work/ws" && cargo build --release --bins --target-dir "$target" \
    && cargo test --release -p physvid-estimator --features cuda-tests --test cuda --no-run \
         --target-dir "$target")
}
if ! build > "$work/log" 2>&1; then
  grep -o 'torch_api_generated.cpp:[0-9]*:[0-9]*: error' "$work/log" | cut -d: -f2 | sort -un > "$work/lines"
  [ -s "$work/lines" ] || { tail -20 "$work/log"; exit 1; }
  python3 - "$work/torch-sys/libtch/torch_api_generated.cpp" "$work/lines" <<'PY'
import sys
path, errs = sys.argv[1], [int(x) for x in open(sys.argv[2]).read().split()]
lines = open(path).read().split("\n")
spans = set()
for e in errs:
    i = e - 1
    while not (lines[i] and not lines[i][0].isspace() and lines[i].rstrip().endswith("{")):
        i -= 1
    j = e - 1
    while lines[j] != "}":
        j += 1
    spans.add((i, j))
for i, j in sorted(spans, reverse=True):
    name = lines[i].split("(")[0].split()[-1]
    lines[i + 1:j] = ["  PROTECT(", f'    throw std::runtime_error("{name} is not in this libtorch");', "  )"]
open(path, "w").write("\n".join(lines))
print(f"{len(spans)} wrapper functions stubbed")
PY
  build > "$work/log" 2>&1 || { tail -20 "$work/log"; exit 1; }
fi
test_bin=$(grep 'Executable tests/cuda.rs' "$work/log" | sed 's/.*(\(.*\))/\1/')
cp "$target/release/gen" "$target/release/estimate" "$out/" && cp "$test_bin" "$out/cuda-test"
strip "$out/gen" "$out/estimate" "$out/cuda-test"
echo "built in $out (the CUDA test expects gen and estimate at $target/release)"
rm -rf "$work"
