#!/usr/bin/env bash
# Benchmark of the Python package against the command line on the same data (measured in this
# run, alternating, REPEAT times each, 2 threads): `estimate DATA` as a process, and
# `physvid.estimate(DATA)` in one Python process (import and torch's load counted once, apart).
# Prints each wall time, the ratio Python / CLI, and whether the answers agree.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
REPEAT="${REPEAT:-3}"
scripts/setup.sh
cargo build --release --quiet --bin estimate --bin gen
.venv/bin/python -m pip install --quiet --disable-pip-version-check ./python
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
./target/release/gen --scenario intensity --samples 500 --size 50 --seed 0 --out "$tmp/set" > /dev/null
.venv/bin/python - "$tmp" "$REPEAT" <<'PY'
import json, subprocess, sys, time
tmp, repeat = sys.argv[1], int(sys.argv[2])
t = time.time()
import physvid
load = time.time() - t
cli_s, py_s, same = [], [], True
for i in range(repeat):
    t = time.time()
    subprocess.run(["target/release/estimate", f"{tmp}/set", "--threads", "2", "--quiet",
                    "--out", f"{tmp}/cli"], check=True, capture_output=True)
    cli_s.append(time.time() - t)
    want = {p["name"]: p["estimate"] for p in json.load(open(f"{tmp}/cli/report.json"))["parameters"]}
    t = time.time()
    r = physvid.estimate(f"{tmp}/set", threads=2, progress=False)
    py_s.append(time.time() - t)
    same &= {n: p.value for n, p in r.parameters.items()} == want
cli, py = min(cli_s), min(py_s)
print(f"intensity 500×50×50, {repeat} runs each (best): CLI {cli:.2f} s, Python {py:.2f} s "
      f"(import physvid + torch {load:.2f} s, once): ratio Python/CLI {py / cli:.2f}; "
      f"answers {'identical' if same else 'DIFFER'}")
PY
