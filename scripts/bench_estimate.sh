#!/usr/bin/env bash
# Benchmark of `estimate` on the default intensity set (2 threads), beside a PyTorch script of
# the same algorithm (scripts/reference_estimate.py) run in the same invocation: epochs per
# second, wall time until γ0 stays within 1 % of its final value, and the whole run's wall time.
# Speed is measured here, never asserted in tests (machines are noisy).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
scripts/setup.sh
cargo build --release --quiet --bin gen --bin estimate
[ -f data/intensity/meta.json ] || ./target/release/gen --scenario intensity --out data/intensity --force > /dev/null
tmp=$(mktemp -d)
start=$(date +%s.%N)
./target/release/estimate data/intensity --threads 2 --out "$tmp/ours" --quiet > /dev/null
end=$(date +%s.%N)
ours=$(.venv/bin/python - "$tmp/ours/report.json" "$start" "$end" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
h = r["history"]
final = next(p["estimate"] for p in r["parameters"] if p["name"] == "gamma0")
i = next(i for i in range(len(h)) if all(abs(x["parameters"][0] / final - 1) <= 0.01 for x in h[i:]))
print(json.dumps({"gamma0": final, "gamma1": r["parameters"][1]["estimate"], "epochs": r["epochs_run"],
    "epochs_per_s": len(h) / h[-1]["elapsed_s"], "wall_s": float(sys.argv[3]) - float(sys.argv[2]),
    "within_1pct_epoch": h[i]["epoch"], "within_1pct_s": h[i]["elapsed_s"]}))
PY
)
ref=$(.venv/bin/python scripts/reference_estimate.py data/intensity 2)
rm -rf "$tmp"
.venv/bin/python - "$ours" "$ref" <<'PY'
import json, sys
o, r = json.loads(sys.argv[1]), json.loads(sys.argv[2])
print(f"{'':22}{'estimate (tch)':>16}{'PyTorch script':>16}{'ratio':>8}")
for k, label in [("epochs_per_s", "epochs / s"), ("within_1pct_epoch", "epochs to γ0 ±1 %"),
                 ("within_1pct_s", "seconds to γ0 ±1 %"), ("epochs", "epochs run"), ("wall_s", "wall time (s)")]:
    print(f"{label:22}{o[k]:>16.2f}{r[k]:>16.2f}{o[k] / r[k]:>8.2f}")
print(f"{'γ0 / γ1':22}{o['gamma0']:>9.4f}/{o['gamma1']:.4f}{r['gamma0']:>9.4f}/{r['gamma1']:.4f}")
PY
