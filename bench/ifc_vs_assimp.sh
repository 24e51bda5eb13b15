#!/usr/bin/env bash
# An IFC model read and decomposed by Avenues, beside Assimp's own import of it, in the
# same runs: `avenues cells MODEL.ifc --json` times Assimp's ReadFile ("assimp import")
# apart from the slicing into a plan ("IFC to plan") and the decomposition after it. The
# target (issue 17): Office A (487 walls, 99 spaces) read and decomposed in under 10 s.
#
# Usage: bench/ifc_vs_assimp.sh [BUILD_DIR] [RUNS] [MODEL.ifc ...]
#   BUILD_DIR  holding app/avenues (default: build beside this script's repository)
#   RUNS       runs per model, the median reported (default 5)
#   MODEL.ifc  default: ../shared/outside/ifc/{duplex,Office_A_20110811}.ifc and the FZK house
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
runs=${2:-5}
shift 2 || true
models=("$@")
if [ ${#models[@]} -eq 0 ]; then
  models=("$here/../shared/outside/ifc/duplex.ifc" "$here/../shared/outside/ifc/Office_A_20110811.ifc"
          /usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc)
fi
avenues=${AVENUES:-$build/app/avenues}

echo "| model | Assimp import | IFC to plan | decompose | total | total / import | cells | named rooms |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for m in "${models[@]}"; do
  for ((i = 0; i < runs; ++i)); do "$avenues" cells "$m" --json 2>/dev/null; echo; done | python3 -c '
import json, statistics, sys, os
runs = [json.loads(l) for l in sys.stdin if l.strip()]
def stage(r, name): return r["stages"].get(name, 0.0)
imp = statistics.median(stage(r, "assimp import") for r in runs)
sl = statistics.median(stage(r, "IFC to plan") for r in runs)
tot = statistics.median(r["seconds"] for r in runs)
r = runs[0]
print(f"| {os.path.basename(sys.argv[1])} | {imp:.2f} s | {sl:.2f} s | {tot - imp - sl:.2f} s | {tot:.2f} s | {tot / imp:.2f} | {r[\"cells\"]} | {r[\"named_rooms\"]} |")
' "$m"
done
