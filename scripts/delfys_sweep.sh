#!/usr/bin/env bash
# The Delfys75 bar: each system's three settings rendered by gen (seed 0), default estimate
# (exact/RK4 block) and the paper's Euler block; prints every SI answer with a ground truth
# against Table 4 (the pendulum: L and ζ) and writes $OUT (default results/delfys_sweep.csv).
# About 3 minutes on 2 cores. SYSTEMS="led torricelli" picks systems, INTEGRATORS="exact" the
# blocks.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
OUT="${OUT:-results/delfys_sweep.csv}"
INTEGRATORS="${INTEGRATORS:-exact euler}"
mkdir -p "$(dirname "$OUT")"
cargo build --release --quiet --bin gen --bin estimate
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "system,setting,integrator,parameter,estimate,truth,rel_error,latent_r2,epochs,wall_s" > "$OUT"
SYSTEMS="${SYSTEMS:-led torricelli sliding-block free-fall pendulum}"
for sys in $SYSTEMS; do
  for setting in 1 2 3; do
    ./target/release/gen --scenario "$sys" --setting "$setting" --out "$tmp/$sys-$setting" --force > /dev/null
    for integ in $INTEGRATORS; do
      ./target/release/estimate "$tmp/$sys-$setting" --integrator "$integ" --out "$tmp/r" --quiet > /dev/null 2>&1 || true
      .venv/bin/python - "$tmp/r/report.json" "$sys" "$setting" "$integ" <<'PY' | tee -a "$OUT"
import json, sys
r = json.load(open(sys.argv[1]))
# Every SI answer with a ground truth (the pendulum: L and ζ), else the first value.
rows = [q for q in r["parameters"] if q["units"] == "SI" and q["truth"] is not None] or r["parameters"][:1]
fit = r.get("latent_vs_truth") or {}
for p in rows:
    err = p["relative_error"]
    print(f'{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{p["name"]},{p["estimate"]:.6g},{p["truth"]},'
          f'{"" if err is None else f"{err * 100:+.2f} %"},{fit.get("r2", float("nan")):.5f},{r["epochs_run"]},{r["wall_time_s"]:.1f}')
PY
    done
  done
done
