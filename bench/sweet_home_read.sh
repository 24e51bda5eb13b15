#!/bin/sh
# Reading times of Sweet Home 3D homes (the "read plan" stage of `avenues cells`: the zip,
# the entry, the home tree, the plan, the furniture's models), each home 9 times, median.
# A home holding both entries is also read from copies holding one of them alone
# (made with `zip -d` in a temporary folder), so serialized and XML stand side by side.
#   bench/sweet_home_read.sh [AVENUES] [OUTSIDE] [EXAMPLES]
set -eu
avenues=${1:-build/app/avenues}
outside=${2:-../shared/outside/sweethome}
examples=${3:-/usr/local/share/avenues/sweethome3d-examples}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

median() {  # the median "read plan" seconds of 9 runs of `avenues cells $1`
  for i in 1 2 3 4 5 6 7 8 9; do
    "$avenues" cells "$1" 2>/dev/null | sed -n 's/.*read plan \([0-9.]*\),.*/\1/p'
  done | sort -n | sed -n 5p
}

printf '| home | entry read | read plan (median of 9) |\n| --- | --- | ---: |\n'
for f in "$outside"/*.sh3d; do
  name=$(basename "$f")
  case $name in damaged*) continue ;; esac
  entries=$(unzip -Z1 "$f")
  if echo "$entries" | grep -qx Home && echo "$entries" | grep -qx Home.xml; then
    cp "$f" "$tmp/xml.sh3d" && chmod u+w "$tmp/xml.sh3d" && zip -q -d "$tmp/xml.sh3d" Home
    cp "$f" "$tmp/ser.sh3d" && chmod u+w "$tmp/ser.sh3d" && zip -q -d "$tmp/ser.sh3d" Home.xml
    printf '| %s | Home.xml, with its models | %s s |\n' "$name" "$(median "$tmp/xml.sh3d")"
    printf '| %s | Home (serialized), with its models | %s s |\n' "$name" "$(median "$tmp/ser.sh3d")"
    # The entry alone (no models: boxes stand in), so the two readers are all that differs.
    (cd "$tmp" && unzip -q -o "$f" Home Home.xml && rm -f xml1.sh3d ser1.sh3d &&
      zip -q xml1.sh3d Home.xml && zip -q ser1.sh3d Home)
    printf '| %s | Home.xml alone | %s s |\n' "$name" "$(median "$tmp/xml1.sh3d")"
    printf '| %s | Home (serialized) alone | %s s |\n' "$name" "$(median "$tmp/ser1.sh3d")"
  elif echo "$entries" | grep -qx Home.xml; then
    printf '| %s | Home.xml | %s s |\n' "$name" "$(median "$f")"
  else
    t=$(median "$f")
    if [ -n "$t" ]; then t="$t s"; else t="refused: $("$avenues" cells "$f" 2>&1 >/dev/null | sed 's/.*: the home/the home/' | cut -c1-40)..."; fi
    printf '| %s | Home (serialized) | %s |\n' "$name" "$t"
  fi
done
for f in "$examples"/*.xml; do
  printf '| %s | bare Home.xml | %s s |\n' "$(basename "$f")" "$(median "$f")"
done
