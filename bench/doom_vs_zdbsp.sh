#!/usr/bin/env bash
# Avenues' cells beside zdbsp's GL subsectors, for every map of the Freedoom WADs.
#
# Both cut a Doom map's free space into convex pieces: zdbsp (a BSP node builder) into
# GL subsectors, convex polygons of one sector each, by recursive splitting lines;
# Avenues into convex prism cells (sectors, with the sky above the open ones) by a
# constrained triangulation merged while convex. This prints a Markdown table per map
# (cells, seconds, warnings against subsectors, seconds), the medians, and the ratio of
# cell counts. The aim: under half of zdbsp's count, under 1 s per map.
#
# Usage: bench/doom_vs_zdbsp.sh [BUILD_DIR] [FILE.wad ...]
#   BUILD_DIR  holding app/avenues (default: build beside this script's repository)
#   FILE.wad   default: Debian's freedoom1.wad and freedoom2.wad
# Environment: AVENUES (the executable, default BUILD_DIR/app/avenues), ZDBSP (default
# zdbsp), ZDBSP_FLAGS (default -x: GL nodes only, as a GL port builds them; -g also
# builds the classic nodes and counts their time too).
# Needs zdbsp (Debian package zdbsp) and python3 (to read the binary GL_SSECT lumps
# and the JSON).
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
shift || true
wads=("$@")
if [ ${#wads[@]} -eq 0 ]; then
  wads=(/usr/share/games/doom/freedoom1.wad /usr/share/games/doom/freedoom2.wad)
fi
avenues=${AVENUES:-$build/app/avenues}
zdbsp=${ZDBSP:-zdbsp}
read -r -a zflags <<< "${ZDBSP_FLAGS:--x}"

command -v "$zdbsp" > /dev/null || { echo "doom_vs_zdbsp: $zdbsp not found (apt-get install zdbsp)" >&2; exit 2; }
command -v python3 > /dev/null || { echo "doom_vs_zdbsp: python3 not found" >&2; exit 2; }
[ -x "$avenues" ] || { echo "doom_vs_zdbsp: $avenues is not an executable (build it, or set AVENUES)" >&2; exit 2; }
for wad in "${wads[@]}"; do
  [ -r "$wad" ] || { echo "doom_vs_zdbsp: cannot read $wad (apt-get install freedoom)" >&2; exit 2; }
done

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rows=$tmp/rows.tsv  # wad, map, zdbsp subsectors, zdbsp seconds, avenues cells, avenues seconds, warnings
: > "$rows"

for wad in "${wads[@]}"; do
  # zdbsp: one run over the whole WAD; it prints "----MAP01----" then "0.018 seconds." per map.
  "$zdbsp" "${zflags[@]}" -o "$tmp/gl.wad" "$wad" > "$tmp/zdbsp.log" 2>&1 ||
    { echo "doom_vs_zdbsp: zdbsp failed on $wad:" >&2; tail -5 "$tmp/zdbsp.log" >&2; exit 1; }
  # Per map: the subsectors of its GL_SSECT lump (v1: 4-byte records; v3/v5: "gNd3"/"gNd5"
  # then 8-byte records) and zdbsp's own time for it.
  python3 - "$tmp/gl.wad" "$tmp/zdbsp.log" > "$tmp/zd.tsv" <<'EOF'
import re, struct, sys
data = open(sys.argv[1], 'rb').read()
count, diroff = struct.unpack_from('<ii', data, 4)
lumps = [struct.unpack_from('<ii8s', data, diroff + 16 * i) for i in range(count)]
names = [n.rstrip(b'\0').decode('latin-1') for _, _, n in lumps]
log = open(sys.argv[2], 'rb').read().decode('latin-1').replace('\r', '\n')
seconds = dict(re.findall(r'----(\S+)----\s*\n\s*([0-9.]+) seconds', log))
for i, name in enumerate(names):
    if not name.startswith('GL_') or name in ('GL_VERT', 'GL_SEGS', 'GL_SSECT', 'GL_NODES', 'GL_PVS'):
        continue
    m = name[3:]
    for j in range(i + 1, min(i + 6, count)):
        if names[j] == 'GL_SSECT':
            pos, size, _ = lumps[j]
            head = data[pos:pos + 4]
            n = (size - 4) // 8 if head in (b'gNd3', b'gNd5') else size // 4
            print(f"{m}\t{n}\t{seconds.get(m, 'nan')}")
            break
EOF
  while IFS=$'\t' read -r map subsectors zsec; do
    if "$avenues" cells "$wad:$map" --json > "$tmp/a.json" 2> "$tmp/a.err"; then
      read -r cells asec warnings < <(python3 -c '
import json, sys
j = json.load(open(sys.argv[1]))
print(j["cells"], j["seconds"], len(j.get("warnings", [])))' "$tmp/a.json")
    else
      echo "doom_vs_zdbsp: avenues failed on $wad:$map: $(head -c 300 "$tmp/a.err")" >&2
      cells=nan asec=nan warnings=nan
    fi
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(basename "$wad")" "$map" "$subsectors" "$zsec" "$cells" "$asec" "$warnings" >> "$rows"
  done < "$tmp/zd.tsv"
done

python3 - "$rows" <<'EOF'
import math, statistics, sys
rows = [l.rstrip('\n').split('\t') for l in open(sys.argv[1]) if l.strip()]
print('| map | zdbsp subsectors | zdbsp s | Avenues cells | Avenues s | cells / subsectors | warnings |')
print('| --- | ---: | ---: | ---: | ---: | ---: | ---: |')
ratios, zs, az, zt, at = [], [], [], [], []
def num(s):
    try:
        return float(s)
    except ValueError:
        return math.nan
for wad, m, sub, zsec, cells, asec, warn in rows:
    sub, zsec, cells, asec = num(sub), num(zsec), num(cells), num(asec)
    r = cells / sub if sub > 0 else math.nan
    if not math.isnan(r):
        ratios.append(r); zs.append(sub); az.append(cells)
    if not math.isnan(zsec): zt.append(zsec)
    if not math.isnan(asec): at.append(asec)
    print(f'| {wad}:{m} | {sub:.0f} | {zsec:.3f} | {cells:.0f} | {asec:.3f} | {r:.2f} | {warn} |')
med = lambda v: statistics.median(v) if v else math.nan
print()
print(f'maps: {len(rows)}; median subsectors {med(zs):.0f}, median cells {med(az):.0f}; '
      f'median cells / subsectors {med(ratios):.2f} (total {sum(az):.0f} / {sum(zs):.0f} = {sum(az) / max(sum(zs), 1):.2f}); '
      f'median seconds: zdbsp {med(zt):.3f}, Avenues {med(at):.3f}; slowest Avenues map {max(at, default=math.nan):.3f} s')
print(f'aim: cells under half of subsectors ({"met" if med(ratios) < 0.5 else "not met"}), '
      f'every map under 1 s ({"met" if at and max(at) < 1 else "not met"})')
EOF
