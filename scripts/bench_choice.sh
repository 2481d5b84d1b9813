#!/usr/bin/env bash
# Benchmark of `estimate VIDEO` with the model left to the tool (issue 63's bar: within 10× the
# time ffmpeg takes to decode the same file, and within 2 GB of memory on a 1080p recording),
# measured in this run on each shared recording (../shared/real-videos/, or the files given as
# arguments): plain ffmpeg decoding the file to nothing (the reference, best of RUNS), then
# `estimate FILE --seed 0 --threads THREADS` (best of RUNS), their wall times, the ratio, the
# estimate's peak memory, the model chosen and the grade. RUNS defaults to 1, THREADS to 2.
# Needs ffmpeg (scripts/setup.sh installs it where it can).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
RUNS="${RUNS:-1}"
THREADS="${THREADS:-2}"
scripts/setup.sh
cargo build --release --quiet --bin estimate
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp target/release/estimate "$tmp/estimate"
if [ "$#" -gt 0 ]; then
  videos=("$@")
else
  videos=()
  for v in ../shared/real-videos/*; do
    case "$v" in *.md) ;; *) videos+=("$v") ;; esac
  done
fi
[ "${#videos[@]}" -gt 0 ] || { echo "bench_choice: no recordings found" >&2; exit 2; }

# The best of RUNS wall times (seconds) of a command, and its largest peak memory (KiB).
best() {
  local i
  : > "$tmp/times"
  for i in $(seq "$RUNS"); do
    /usr/bin/time -f "%e %M" -a -o "$tmp/times" "$@" > /dev/null 2>&1 || true
  done
  # time(1) adds "Command exited with non-zero status N" where the run exits so (4: an
  # unreliable answer); the figures are the lines of numbers.
  grep -E '^[0-9]' "$tmp/times" > "$tmp/figures"
  sort -n "$tmp/figures" | head -1 | cut -d' ' -f1
  sort -k2 -n "$tmp/figures" | tail -1 | cut -d' ' -f2
}

printf '%-26s %9s %10s %7s %9s  %-18s %s\n' recording "decode s" "estimate s" ratio "peak MiB" chosen grade
ratios=()
peaks=()
for v in "${videos[@]}"; do
  read -r decode _ < <(best ffmpeg -v error -nostdin -i "$v" -f null - | paste -sd' ')
  rm -rf "$tmp/run"
  read -r wall kb < <(best "$tmp/estimate" "$v" --seed 0 --threads "$THREADS" --out "$tmp/run" --force --quiet | paste -sd' ')
  read -r model grade < <(.venv/bin/python - "$tmp/run/report.json" <<'PY'
import json, sys
try:
    r = json.load(open(sys.argv[1]))
    print(r["model"], r["verdict"]["grade"])
except (OSError, ValueError, KeyError):
    print("(none) (no-report)")
PY
)
  ratio=$(python3 -c "print(f'{$wall / max($decode, 1e-3):.1f}')")
  ratios+=("$ratio")
  peaks+=("$((kb / 1024))")
  printf '%-26s %9s %10s %7s %9s  %-18s %s\n' "$(basename "$v")" "$decode" "$wall" "${ratio}×" \
    "$((kb / 1024))" "$model" "$grade"
done
python3 - "${#ratios[@]}" "${ratios[@]}" "${peaks[@]}" <<'PY'
import statistics, sys
n = int(sys.argv[1])
r = sorted(float(x) for x in sys.argv[2:2 + n])
peaks = [int(x) for x in sys.argv[2 + n:]]
print(f"ratio estimate / decode over {len(r)} recordings: median {statistics.median(r):.1f}×, "
      f"largest {r[-1]:.1f}×, within 10×: {sum(x <= 10 for x in r)} of {len(r)}")
# The bar's 2 GB as 2·10⁹ bytes (1907 MiB), the stricter reading.
bar = 2e9 / 2**20
print(f"peak memory: largest {max(peaks)} MiB, within 2 GB ({bar:.0f} MiB): "
      f"{sum(p <= bar for p in peaks)} of {len(peaks)}")
PY
