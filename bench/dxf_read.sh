#!/bin/sh
# Reading times of DXF floor plans: the "read drawing" stage of `avenues cells` (dxflib,
# blocks placed, wall line ends closed, the CGAL arrangement, doors and windows, the Plan)
# against the same plan saved with --save-plan and read back as TOML ("read plan"), each
# 9 times, interleaved, median; the ratio is what understanding the drawing costs over
# reading the plan it became. What each drawing gave is the reader's last summary line.
#   bench/dxf_read.sh [AVENUES] [OUTSIDE]
set -eu
avenues=${1:-build/app/avenues}
outside=${2:-../shared/outside/dxf}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

stage() {  # the seconds of stage $2 in `avenues cells $1`
  "$avenues" cells "$1" 2>/dev/null | sed -n "s/.*$2 \([0-9.]*\),.*/\1/p"
}

printf '| drawing | understood | read drawing | read plan (TOML) | ratio |\n| --- | --- | ---: | ---: | ---: |\n'
for f in "$outside"/*.dxf; do
  name=$(basename "$f")
  if ! "$avenues" cells "$f" --save-plan "$tmp/p.toml" >/dev/null 2>"$tmp/err"; then
    printf '| %s | refused: %s... | | | |\n' "$name" "$(tail -1 "$tmp/err" | sed 's/.*dxf: //' | cut -c1-40)"
    continue
  fi
  got=$(grep ' walls, ' "$tmp/err" | sed 's/.*dxf: //' | sed 's/ (.*//')
  : >"$tmp/a"; : >"$tmp/b"
  for i in 1 2 3 4 5 6 7 8 9; do
    stage "$f" 'read drawing' >>"$tmp/a"
    stage "$tmp/p.toml" 'read plan' >>"$tmp/b"
  done
  a=$(sort -n "$tmp/a" | sed -n 5p); b=$(sort -n "$tmp/b" | sed -n 5p)
  printf '| %s | %s | %s s | %s s | %s |\n' "$name" "$got" "$a" "$b" "$(echo "$a $b" | awk '{ if ($2 > 0) printf "%.0fx", $1 / $2; else print "-" }')"
done
