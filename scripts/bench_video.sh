#!/usr/bin/env bash
# Benchmark of decode-and-estimate on pendulum recordings (2 threads), measured in this run:
#  1. the real pendulum recording (../shared/real-videos/pendulum-redapple.mov, 22 s at 59.94 fps),
#     with our decode throughput (ffmpeg → pipe → crop/area resize) beside plain ffmpeg decoding
#     the same file to nothing, and the answers against the tracked period (g/L = 9.15 s⁻²);
#  2. a 30-s 60-fps 640×360 pendulum video drawn here (L = 0.9 m, ζ = 0.02 s⁻¹, 20°), the size
#     of a typical lab recording.
# With REF=REV (a git revision), that revision's `estimate` is built in a worktree (into
# target/bench-ref) and every recording is run by both, in turn, RUNS times each (default 2):
# the best wall time and the least and largest peak memory of each, and their ratios (this
# tree / REV).
# Needs ffmpeg (scripts/setup.sh installs it where it can).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
VIDEO="${VIDEO:-../shared/real-videos/pendulum-redapple.mov}"
REF="${REF:-}"
RUNS="${RUNS:-2}"
scripts/setup.sh
cargo build --release --quiet --bin estimate
tmp=$(mktemp -d)
cleanup() {
  [ -n "$REF" ] && git worktree remove --force "$tmp/ref" > /dev/null 2>&1 || true
  rm -rf "$tmp"
}
trap cleanup EXIT
cp target/release/estimate "$tmp/estimate"
bins=("$tmp/estimate")
if [ -n "$REF" ]; then
  # Built in a target folder of its own, kept between runs (target/bench-ref): a workspace's
  # crates are hashed alike wherever they lie, so a shared folder would mix the two trees.
  git worktree add --detach "$tmp/ref" "$REF" > /dev/null
  cp -r .cargo "$tmp/ref/" 2> /dev/null || true
  ln -s "$root/.venv" "$tmp/ref/.venv"
  echo "building $REF's estimate in target/bench-ref (the first time: minutes)" >&2
  (cd "$tmp/ref" && CARGO_TARGET_DIR="$root/target/bench-ref" cargo build --release --quiet --bin estimate)
  cp target/bench-ref/release/estimate "$tmp/estimate.ref"
  bins+=("$tmp/estimate.ref")
fi

# Runs each binary on a recording RUNS times in turn; prints the best wall time, the peak
# memory, decode timing and the answers of each, and with REF their ratios.
measure() {
  local video=$1 label=$2 i b
  : > "$tmp/times"
  for i in $(seq "$RUNS"); do
    for b in "${!bins[@]}"; do
      /usr/bin/time -f "$b %e %M" -a -o "$tmp/times" "${bins[$b]}" "$video" --model pendulum \
        --threads 2 --out "$tmp/run$b" --force --quiet > /dev/null 2>&1
    done
  done
  .venv/bin/python - "$tmp" "${#bins[@]}" "$label" "${REF:-}" <<'PY'
import json, sys
tmp, n, label, ref = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
# Per binary: the best wall time, and the least and the largest peak memory of its runs (the
# peak varies from run to run by up to half on the same input: the allocator's arenas).
best = {}
for line in open(f"{tmp}/times"):
    b, wall, kb = line.split()
    w, lo, hi = best.get(int(b), (float("inf"), float("inf"), 0))
    best[int(b)] = (min(w, float(wall)), min(lo, int(kb)), max(hi, int(kb)))
print(f"{label}:")
for b in range(n):
    r = json.load(open(f"{tmp}/run{b}/report.json"))
    rec = r["recording"]
    v = {p["name"]: p["estimate"] for p in r["parameters"]}
    who = "this tree" if b == 0 else f"REF {ref}"
    print(f"  {who}: decode + estimate {best[b][0]:.1f} s wall (best of runs), peak {best[b][1] / 1024:.0f}–{best[b][2] / 1024:.0f} MiB "
          f"(decode {rec['decode_s']:.1f} s, {rec['frames_decoded']} frames at {rec['decode_fps']:.0f} frames/s; "
          f"{r['epochs_run']} epochs, {rec['clips']} clips); g/L {v['g_over_l']:.3f} s^-2, damping {v['damping']:.4f} s^-1")
    c = r.get("cross_check")
    if c:
        print(f"    damping from the swing amplitudes' decay (appendix A.6): {c['estimate']:.4f} ± {c['std_error']:.4f} s^-1 "
              f"from {len(c['peaks'])} swings")
if n == 2:
    print(f"  ratio this tree / REF: wall {best[0][0] / best[1][0]:.2f}, peak memory {best[0][1] / best[1][1]:.2f} "
          f"(least of runs; largest {best[0][2] / best[1][2]:.2f})")
PY
}

if [ -f "$VIDEO" ]; then
  frames=$(ffprobe -v error -select_streams v:0 -count_packets -show_entries stream=nb_read_packets -of csv=p=0 "$VIDEO")
  t0=$(date +%s.%N)
  ffmpeg -v error -nostdin -i "$VIDEO" -f null -
  t1=$(date +%s.%N)
  echo "plain ffmpeg decoding $VIDEO to null: $(python3 -c "print(f'{$frames / ($t1 - $t0):.0f}')") frames/s"
  measure "$VIDEO" "real pendulum (g/L from its tracked period: 9.15 s^-2)"
else
  echo "bench_video: $VIDEO not found; skipping the real recording" >&2
fi

# A 30-s 60-fps pendulum drawn with numpy: a bright bob on a string over a grey gradient.
.venv/bin/python - <<'PY' | ffmpeg -v error -nostdin -f rawvideo -pix_fmt gray -s 640x360 -r 60 -i - \
    -c:v libx264 -pix_fmt yuv420p -crf 18 "$tmp/pendulum30s.mp4"
import math, sys
import numpy as np
w2, zeta, dt, th, om = 9.81 / 0.9, 0.02, 1 / 60, math.radians(20), 0.0
yy, xx = np.mgrid[0:360, 0:640].astype(np.float32)
background = (60 + 40 * xx / 640).astype(np.float32)
for _ in range(1800):
    bx, by = 320 + 250 * math.sin(th), 20 + 250 * math.cos(th)
    frame = background.copy()
    t = np.clip(((xx - 320) * (bx - 320) + (yy - 20) * (by - 20)) / (250 * 250), 0, 1)
    d_line = np.hypot(xx - (320 + t * (bx - 320)), yy - (20 + t * (by - 20)))
    frame[d_line < 1.5] = 200
    frame[np.hypot(xx - bx, yy - by) < 18] = 240
    sys.stdout.buffer.write(frame.astype(np.uint8).tobytes())
    for _ in range(16):  # RK4, 16 sub-steps per frame
        h = dt / 16
        f = lambda a, b: (b, -w2 * math.sin(a) - zeta * b)
        k1 = f(th, om); k2 = f(th + h / 2 * k1[0], om + h / 2 * k1[1])
        k3 = f(th + h / 2 * k2[0], om + h / 2 * k2[1]); k4 = f(th + h * k3[0], om + h * k3[1])
        th += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]); om += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
PY
measure "$tmp/pendulum30s.mp4" "30-s 60-fps pendulum drawn here (g/L 10.900 s^-2, damping 0.0200 s^-1)"
