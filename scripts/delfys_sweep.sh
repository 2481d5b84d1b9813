#!/usr/bin/env bash
# The Delfys75 bar of issue 4: each system's three settings rendered by gen (seed 0), default
# estimate (exact/RK4 block) and the paper's Euler block; prints the SI answer against Table 4
# and writes $OUT (default results/delfys_sweep.csv). About 12 minutes on 2 cores, most of it the
# pendulum (60-100 s per run of its RK4 block). SYSTEMS="led torricelli" picks systems.
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
p = next(q for q in r["parameters"] if q["units"] == "SI" and q["truth"] is not None) if any(
    q["units"] == "SI" and q["truth"] is not None for q in r["parameters"]) else r["parameters"][0]
fit = r.get("latent_vs_truth") or {}
err = p["relative_error"]
print(f'{sys.argv[2]},{sys.argv[3]},{sys.argv[4]},{p["name"]},{p["estimate"]:.6g},{p["truth"]},'
      f'{"" if err is None else f"{err * 100:+.2f} %"},{fit.get("r2", float("nan")):.5f},{r["epochs_run"]},{r["wall_time_s"]:.1f}')
PY
    done
  done
done
