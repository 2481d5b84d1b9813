#!/usr/bin/env bash
# Benchmark of `estimate` on a CUDA GPU against the CPU of the same machine, measured in this one
# run: for each default set (the intensity oscillator, the pendulum at setting 2, the spring) the
# same command with `--device cuda` and with `--device cpu --threads $(nproc)`, each run's
# whole-process wall time, epochs, median epoch time and answers, and the CPU/GPU ratios
# (speed is measured here, never asserted in tests). Needs an NVIDIA GPU and an `estimate` whose
# libtorch has CUDA (the PyPI wheel that scripts/setup.sh installs has).
#   BIN        folder holding `gen` and `estimate` (default target/release, built if cargo exists)
#   SETS       which sets (default "intensity pendulum2 spring")
#   DEVICES    which devices (default "cuda cpu")
#   CPU_EPOCHS caps the CPU runs at this many epochs (their epoch time is still compared; their
#              whole-process ratio is then left out), for sets whose CPU run takes too long
#   MD         also write the table as Markdown to this file
#   PY         a Python 3 (default .venv/bin/python, else python3)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
BIN="${BIN:-target/release}"
SETS="${SETS:-intensity pendulum2 spring}"
DEVICES="${DEVICES:-cuda cpu}"
PY="${PY:-$([ -x .venv/bin/python ] && echo .venv/bin/python || echo python3)}"
if [ ! -x "$BIN/estimate" ] && command -v cargo > /dev/null; then
  cargo build --release --quiet --bin gen --bin estimate
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
gpu=$(nvidia-smi --query-gpu=name --format=csv,noheader 2> /dev/null | head -1 || true)
echo "GPU: ${gpu:-none found}"

# The gen arguments of a set.
gen_args() {
  case $1 in
    intensity) echo "--scenario intensity" ;;
    pendulum2) echo "--scenario pendulum --setting 2" ;;
    spring) echo "--scenario spring" ;;
    *) echo "unknown set $1" >&2; exit 2 ;;
  esac
}

# Runs `estimate DATA --device DEV [extra]` and prints a JSON line of its figures.
run() {
  local set=$1 dev=$2; shift 2
  local out=$tmp/run-$set-$dev start end
  start=$(date +%s.%N)
  "$BIN/estimate" "$tmp/$set" --device "$dev" --threads "$(nproc)" --out "$out" --quiet "$@" > /dev/null
  end=$(date +%s.%N)
  "$PY" - "$out/report.json" "$start" "$end" "$set" "$dev" "$#" <<'PY'
import json, statistics, sys
r = json.load(open(sys.argv[1]))
h = r["history"]
steps = [b["elapsed_s"] - a["elapsed_s"] for a, b in zip(h[8:], h[9:])]
print(json.dumps({"set": sys.argv[4], "device": sys.argv[5], "capped": sys.argv[6] != "0",
    "wall_s": float(sys.argv[3]) - float(sys.argv[2]), "epochs": r["epochs_run"],
    "epoch_s": statistics.median(steps) if steps else float("nan"),
    "values": {p["name"]: p["estimate"] for p in r["parameters"]},
    "errors": {p["name"]: p["relative_error"] for p in r["parameters"] if p.get("relative_error") is not None},
    "grade": (r.get("verdict") or {}).get("grade"),
    "reasons": [c.get("check") for c in (r.get("verdict") or {}).get("reasons", [])],
    "device_used": r.get("device")}))
PY
}

for set in $SETS; do
  # shellcheck disable=SC2046
  "$BIN/gen" $(gen_args "$set") --out "$tmp/$set" --force > /dev/null
  for dev in $DEVICES; do
    if [ "$dev" = cpu ] && [ -n "${CPU_EPOCHS:-}" ]; then
      run "$set" cpu --epochs "$CPU_EPOCHS" | tee -a "$tmp/lines"
    else
      run "$set" "$dev" | tee -a "$tmp/lines"
    fi
  done
done

"$PY" - "$tmp/lines" "$(nproc)" "${MD:-}" "${gpu:-no GPU}" "$(date -u +%Y-%m-%d)" <<'PY'
import json, sys
rows = [json.loads(l) for l in open(sys.argv[1])]
head = (f"Written by `scripts/bench_gpu.sh` on {sys.argv[4]} beside {sys.argv[2]} CPU threads, "
        f"{sys.argv[5]}: each default set's `estimate` with `--device cuda` and `--device cpu "
        f"--threads {sys.argv[2]}` on the same machine; epoch time is the median after epoch 9.\n")
by = {(r["set"], r["device"]): r for r in rows}
lines = [f"| set | device | wall s | epochs | epoch ms | CPU/GPU epoch | CPU/GPU wall | answers (error) | grade |",
         "|---|---|---|---|---|---|---|---|---|"]
for r in rows:
    g = by.get((r["set"], "cuda"))
    ratio_e = r["epoch_s"] / g["epoch_s"] if g and r["device"] == "cpu" else None
    ratio_w = r["wall_s"] / g["wall_s"] if g and r["device"] == "cpu" and not r["capped"] else None
    ans = ", ".join(f"{k} {v:.5g}" + (f" ({r['errors'][k] * 100:+.2f} %)" if k in r["errors"] else "")
                    for k, v in r["values"].items())
    dev = r["device"] + (f" ({sys.argv[2]} threads)" if r["device"] == "cpu" else "")
    lines.append(f"| {r['set']} | {dev} | {r['wall_s']:.1f} | {r['epochs']}{' (capped)' if r['capped'] else ''} | "
                 f"{r['epoch_s'] * 1e3:.1f} | {'' if ratio_e is None else f'{ratio_e:.2f}'} | "
                 f"{'' if ratio_w is None else f'{ratio_w:.2f}'} | {ans} | {r['grade']} |")
text = "\n".join(lines)
print(text)
if sys.argv[3]:
    open(sys.argv[3], "w").write("# estimate on a GPU\n\n" + head + "\n" + text + "\n")
PY
