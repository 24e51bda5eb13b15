#!/usr/bin/env bash
# Two builds of Avenues measured by the same benchmarks, taking turns: what a change did to
# the figures in docs/PERFORMANCE.md (cells, visibility, half-tone, the walkthrough window).
#
# Each round runs the "before" build, then the "after" build (the order swapped every other
# round, so that neither always runs on a warmer or a busier machine):
#   - avenues_bench (Google Benchmark) with FILTER: decomposition of the bundled plans and
#     the 10 x 10 and 30 x 30 offices, loading the 100 x 100 office's complex, traversal per
#     view, the 1920 x 1080 half-tone frames;
#   - `avenues bench walk` in one Xvfb server at 1280 x 720 with no frame budget: the bundled plans
#     and, when installed (.ci/install-deps), two furnished Sweet Home 3D houses.
# Then, per benchmark, the median over the rounds of each build and their ratio after/before.
#
# Usage: bench/before_after.sh BEFORE_BUILD AFTER_BUILD [ROUNDS] [WALK_FRAMES]
#   BEFORE_BUILD, AFTER_BUILD  build folders, each holding app/avenues and bench/avenues_bench
#                              (cmake --build DIR --target avenues avenues_bench)
#   ROUNDS                     default 3
#   WALK_FRAMES                frames per plan in the walk, default 300
# Environment: FILTER (avenues_bench's --benchmark_filter), WALK_PLANS (space-separated).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
before=${1:?usage: bench/before_after.sh BEFORE_BUILD AFTER_BUILD [ROUNDS] [WALK_FRAMES]}
after=${2:?usage: bench/before_after.sh BEFORE_BUILD AFTER_BUILD [ROUNDS] [WALK_FRAMES]}
rounds=${3:-3}
frames=${4:-300}
filter=${FILTER:-'^build/(jones-house|furnished-room|two-storey-house|office-corridor|curved-walls|office-10x10|office-30x30)$|^load/|^Visibility/[a-z-]+\.toml/(double|exact)$|^Visibility/local_view|^halftone_frame|memset'}
homes=/usr/local/share/avenues/sweethome3d-examples
plans=${WALK_PLANS:-"$root/plans/jones-house.toml $root/plans/two-storey-house.toml $root/plans/office-corridor.toml $root/plans/furnished-room.toml $root/plans/curved-walls.toml"}
for h in 4BedroomHouse 3BedroomHouseWithMezzanine; do
  [[ -z ${WALK_PLANS:-} && -f $homes/$h.xml ]] && plans+=" $homes/$h.xml"
done
for b in "$before" "$after"; do
  [[ -x $b/app/avenues && -x $b/bench/avenues_bench ]] || { echo "$b: no app/avenues or bench/avenues_bench" >&2; exit 2; }
done
work=$(mktemp -d)
# One X server for every walk of the run, which does not reset when its last client leaves
# (each plan's window is one; a resetting server refuses the next for a moment).
display=150
while [[ -e /tmp/.X$display-lock || -e /tmp/.X11-unix/X$display ]]; do display=$((display + 1)); done
Xvfb ":$display" -screen 0 1280x720x24 -nolisten tcp -noreset >/dev/null 2>&1 &
xvfb=$!
trap 'kill "$xvfb" 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 100); do [[ -e /tmp/.X11-unix/X$display ]] && break; sleep 0.1; done
[[ -e /tmp/.X11-unix/X$display ]] || { echo "Xvfb :$display did not start" >&2; exit 1; }
echo "before: $before  after: $after  rounds: $rounds  walk frames: $frames"
echo "avenues_bench --benchmark_filter='$filter'"
echo "walk: avenues bench walk --frames $frames --size 1280x720 $plans"

run_one() {  # run_one SIDE BUILD ROUND
  local side=$1 build=$2 round=$3 budget=()
  (cd "$root" && "$build/bench/avenues_bench" --benchmark_filter="$filter" --benchmark_format=json \
    --benchmark_out="$work/$side-$round.json" --benchmark_out_format=json >/dev/null 2>"$work/err.txt") ||
    { cat "$work/err.txt" >&2; exit 1; }
  # The frame budget came later: where the build has it, it is turned off (as before it).
  "$build/app/avenues" bench walk --help 2>/dev/null | grep -q -- --frame-budget && budget=(--frame-budget 0)
  # shellcheck disable=SC2086  # the plans are words
  DISPLAY=:$display "$build/app/avenues" bench walk --frames "$frames" --size 1280x720 "${budget[@]}" $plans \
    >"$work/$side-$round.walk" 2>"$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
  echo "round $round: $side done"
}

for ((r = 1; r <= rounds; ++r)); do
  if ((r % 2)); then
    run_one before "$before" "$r"
    run_one after "$after" "$r"
  else
    run_one after "$after" "$r"
    run_one before "$before" "$r"
  fi
done

python3 - "$work" "$rounds" <<'EOF'
import json, re, statistics, sys
work, rounds = sys.argv[1], int(sys.argv[2])
def bench(side):
    out = {}
    for r in range(1, rounds + 1):
        runs = json.load(open(f"{work}/{side}-{r}.json"))["benchmarks"]
        # A benchmark that reports only its aggregates (repetitions) counts by its median.
        whole = {b["run_name"] for b in runs if b.get("run_type", "iteration") == "iteration"}
        for b in runs:
            name = b.get("run_name", b["name"])
            if b.get("run_type", "iteration") != "iteration" and (name in whole or b.get("aggregate_name") != "median"):
                continue
            scale = {"ns": 1e-3, "us": 1, "ms": 1e3, "s": 1e6}[b["time_unit"]]
            out.setdefault(name, []).append(b["real_time"] * scale)
    return out
def walk(side):
    out = {}
    row = re.compile(r"^(\S+)\s+([0-9.]+) ms\s+([0-9.]+) ms\s+([0-9.]+) ms\s+\d+\s+([0-9.]+) ms")
    for r in range(1, rounds + 1):
        for line in open(f"{work}/{side}-{r}.walk"):
            m = row.match(line)
            if m:
                for what, value in zip(("median", "p95", "p99", "render"), m.groups()[1:]):
                    out.setdefault(f"walk/{m.group(1)}/{what}", []).append(float(value) * 1e3)
    return out
b, a = bench("before"), bench("after")
b.update(walk("before"))
a.update(walk("after"))
# Apart: every round of one build slower than every round of the other (the rounds' ranges
# do not overlap), the least a difference must be to stand out of the machine's noise.
print(f"\n{'benchmark':58} {'before':>12} {'after':>12} {'after/before':>13}  apart")
ratios, apart = [], 0
for name in list(b) + [n for n in a if n not in b]:
    if name not in b or name not in a:
        print(f"{name:58} {'(only ' + ('before' if name in b else 'after') + ')':>12}")
        continue
    mb, ma = statistics.median(b[name]), statistics.median(a[name])
    ratios.append(ma / mb)
    sep = "slower" if min(a[name]) > max(b[name]) else "faster" if max(a[name]) < min(b[name]) else ""
    apart += sep != ""
    unit = lambda us: f"{us / 1e3:.3f} ms" if us >= 1e3 else f"{us:.2f} us"
    print(f"{name:58} {unit(mb):>12} {unit(ma):>12} {ma / mb:>12.2f}x  {sep}")
print(f"\nmedian ratio over {len(ratios)} benchmarks: {statistics.median(ratios):.2f}x "
      f"(range {min(ratios):.2f}x to {max(ratios):.2f}x); medians of {rounds} rounds each; "
      f"{apart} apart (every round of one build beyond every round of the other)")
EOF
