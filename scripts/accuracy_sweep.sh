#!/usr/bin/env bash
# Accuracy sweep of issue 3's bar: default `estimate` on the default intensity, position and
# scale sets, seeds 0-4, both integrators, from the default start and from --init gamma0=10 and
# gamma0=0.5. Prints one line per run and a summary; writes results to $OUT (default
# results/accuracy_sweep.csv). Takes about 15 minutes on 2 cores.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
OUT="${OUT:-results/accuracy_sweep.csv}"
mkdir -p "$(dirname "$OUT")" data
cargo build --release --quiet --bin gen --bin estimate
for s in intensity position scale; do
    [ -f "data/$s/meta.json" ] || ./target/release/gen --scenario "$s" --out "data/$s" --force > /dev/null
done
echo "scenario,integrator,init,seed,gamma0,gamma1,epochs,wall_s" > "$OUT"
tmp=$(mktemp -d)
for integ in exact euler; do
  for init in default gamma0=10 gamma0=0.5; do
    for s in intensity position scale; do
      for seed in 0 1 2 3 4; do
        args=(--integrator "$integ" --seed "$seed" --out "$tmp/r" --quiet)
        [ "$init" = default ] || args+=(--init "$init")
        ./target/release/estimate "data/$s" "${args[@]}" > /dev/null
        line=$(.venv/bin/python - "$tmp/r/report.json" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
p = {q["name"]: q["estimate"] for q in r["parameters"]}
print(f'{p["gamma0"]:.5f},{p["gamma1"]:.5f},{r["epochs_run"]},{r["wall_time_s"]:.2f}')
PY
)
        echo "$s,$integ,$init,$seed,$line" | tee -a "$OUT"
      done
    done
  done
done
rm -rf "$tmp"
.venv/bin/python - "$OUT" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
target = {"exact": (4.0016, 0.08), "euler": (3.917, 0.0794)}
for integ, (g0, g1) in target.items():
    sel = [r for r in rows if r["integrator"] == integ]
    ok = [r for r in sel if abs(float(r["gamma0"]) / g0 - 1) <= 0.005 and abs(float(r["gamma1"]) / g1 - 1) <= 0.05]
    worst0 = max(abs(float(r["gamma0"]) / g0 - 1) for r in sel) * 100
    worst1 = max(abs(float(r["gamma1"]) / g1 - 1) for r in sel) * 100
    times = sorted(float(r["wall_s"]) for r in sel)
    print(f"{integ}: {len(ok)}/{len(sel)} within 0.5 % (γ0 {g0}) and 5 % (γ1 {g1}); worst γ0 {worst0:.3f} %, worst γ1 {worst1:.2f} %; wall median {times[len(times)//2]:.1f} s, max {times[-1]:.1f} s")
PY
