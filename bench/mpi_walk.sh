#!/usr/bin/env bash
# An MPI walk beside one process, and the cost of broadcasting a large complex.
#
# 1. A 1920 x 1080, 16-sample half-tone walk of plans/two-storey-house.toml, rendered by one
#    process with one thread (--threads 1) and by `mpirun -np 2` (each rank its share of
#    the cores: one thread on a 2-core machine), alternately, REPEATS times each; prints
#    each run's seconds, the medians and their ratios: of the whole command (which ends
#    with the film, encoded by rank 0 alone) and of the frames (the "wrote N frames in
#    T s" avenues prints: the walk's frames on all its ranks, from first to last).
# 2. The 100 x 100 office (avenues generate office --rooms 100x100), decomposed once and
#    saved as .cells, walked by `mpirun -np 2` for a few drawn frames: rank 0 prints what
#    it broadcast (the complex and the cameras) and how long that took.
#
# Usage: bench/mpi_walk.sh [BUILD_DIR] [REPEATS]
#   BUILD_DIR  holding app/avenues (default: build beside this script's repository)
#   REPEATS    runs of each kind (default 3)
# Environment: STEP (metres between frames, default 0.5: 12 frames; 0.1: 58), MPIRUN (default mpirun; --allow-run-as-root and --oversubscribe are added,
# and --bind-to none for the walk: the one process it is compared with is not bound either).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$root/build}
repeats=${2:-3}
avenues=$build/app/avenues
mpirun=${MPIRUN:-mpirun}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
house=$root/plans/two-storey-house.toml
walk=(path "$house" --through "hall,living room" --step "${STEP:-0.5}" --size 1920x1080 --samples 16)

seconds() {  # seconds COMMAND...: runs it quietly, prints its wall-clock seconds
  local t0 t1
  t0=$(date +%s.%N)
  "$@" >"$work/out.txt" 2>"$work/err.txt" || { cat "$work/err.txt" >&2; exit 1; }
  t1=$(date +%s.%N)
  python3 -c "print(f'{$t1 - $t0:.2f}')"
}
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }

echo "walk: avenues ${walk[*]}"
frames_s() { grep -o 'frames in [0-9.]* s' "$work/out.txt" | grep -o '[0-9.]* s' | cut -d' ' -f1; }
one=() two=() one_f=() two_f=()
for ((i = 1; i <= repeats; ++i)); do
  one+=("$(seconds "$avenues" "${walk[@]}" --threads 1 -o "$work/one")")
  one_f+=("$(frames_s)")
  two+=("$(seconds "$mpirun" --allow-run-as-root --oversubscribe --bind-to none -np 2 "$avenues" "${walk[@]}" -o "$work/two")")
  two_f+=("$(frames_s)")
  echo "run $i: one process, one thread ${one[-1]} s (frames ${one_f[-1]} s); mpirun -np 2 ${two[-1]} s (frames ${two_f[-1]} s)"
done
cmp -s <(cd "$work/one" && cat frame-*.png | sha1sum) <(cd "$work/two" && cat frame-*.png | sha1sum) ||
  { echo "the frames differ" >&2; exit 1; }
ratio() { python3 -c "print(f'{$1 / $2:.2f}')"; }
m1=$(median "${one[@]}") m2=$(median "${two[@]}") f1=$(median "${one_f[@]}") f2=$(median "${two_f[@]}")
echo "median, whole command: one process, one thread $m1 s; mpirun -np 2 $m2 s; speed-up $(ratio "$m1" "$m2")x"
echo "median, the frames:    one process, one thread $f1 s; mpirun -np 2 $f2 s; speed-up $(ratio "$f1" "$f2")x"
echo
echo "broadcast: the 100 x 100 office"
"$avenues" generate office --rooms 100x100 -o "$work/office.toml" >/dev/null
"$avenues" cells "$work/office.toml" --save "$work/office.cells" >/dev/null
for ((i = 1; i <= repeats; ++i)); do
  "$mpirun" --allow-run-as-root --oversubscribe -np 2 "$avenues" path "$work/office.cells" --through "r0_0,r0_1" \
    --format svg --size 64x36 --step 1 -o "$work/office" | grep -o '[0-9]* rendered on .*'
done
