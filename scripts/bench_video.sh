#!/usr/bin/env bash
# Benchmark of issue 5: decode-and-estimate on the real pendulum recording (2 threads), with the
# decode throughput of our path (ffmpeg → pipe → crop/area resize) beside plain ffmpeg decoding
# the same file to nothing, run in the same script. Needs ../shared/real-videos and ffmpeg.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
VIDEO="${VIDEO:-../shared/real-videos/pendulum-redapple.mov}"
[ -f "$VIDEO" ] || { echo "bench_video: $VIDEO not found" >&2; exit 1; }
cargo build --release --quiet --bin estimate
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
frames=$(ffprobe -v error -select_streams v:0 -count_packets -show_entries stream=nb_read_packets -of csv=p=0 "$VIDEO")
t0=$(date +%s.%N)
ffmpeg -v error -nostdin -i "$VIDEO" -f null - 
t1=$(date +%s.%N)
plain=$(python3 -c "print(f'{$frames / ($t1 - $t0):.0f}')")
start=$(date +%s.%N)
./target/release/estimate "$VIDEO" --model pendulum --threads 2 --out "$tmp/run" --quiet > /dev/null
end=$(date +%s.%N)
python3 - "$tmp/run/report.json" "$plain" "$start" "$end" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
rec = r["recording"]
plain = float(sys.argv[2])
total = float(sys.argv[4]) - float(sys.argv[3])
print(f"decode: {rec['frames_decoded']} frames in {rec['decode_s']:.2f} s = {rec['decode_fps']:.0f} frames/s "
      f"(plain ffmpeg to null: {plain:.0f} frames/s, ratio {rec['decode_fps'] / plain:.2f})")
w2 = next(p["estimate"] for p in r["parameters"] if p["name"] == "g_over_l")
print(f"decode + estimate: {total:.1f} s wall ({r['epochs_run']} epochs, {rec['clips']} clips), "
      f"g/L = {w2:.3f} s^-2 (period: 9.15, {100 * (w2 / 9.15 - 1):+.1f} %)")
PY
