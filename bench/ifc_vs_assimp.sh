#!/usr/bin/env bash
# An IFC model read and decomposed by Avenues, beside Assimp's own import of it, in the
# same runs: `avenues cells MODEL.ifc --json` times Assimp's ReadFile ("assimp import")
# apart from the slicing into a plan ("IFC to plan") and the decomposition after it. The
# target (issue 17): Office A (487 walls, 99 spaces) read and decomposed in under 10 s.
#
# Usage: bench/ifc_vs_assimp.sh [BUILD_DIR] [RUNS] [MODEL.ifc ...]
#   BUILD_DIR  holding app/avenues (default: build beside this script's repository)
#   RUNS       runs per model, the median reported (default 5)
#   MODEL.ifc  default: ../shared/outside/ifc/{duplex,Office_A_20110811}.ifc (or under
#              $AVENUES_OUTSIDE) and the FZK house
set -euo pipefail

here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
runs=${2:-5}
shift 2 || true
models=("$@")
outside=$here/../shared/outside
[ -d "$outside" ] || outside=${AVENUES_OUTSIDE:-$outside}
if [ ${#models[@]} -eq 0 ]; then
  models=("$outside/ifc/duplex.ifc" "$outside/ifc/Office_A_20110811.ifc"
          /usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc)
fi
avenues=${AVENUES:-$build/app/avenues}

echo "| model | Assimp import | IFC to plan | decompose | total | total / import | cells | named rooms |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for m in "${models[@]}"; do
  python3 - "$avenues" "$runs" "$m" <<'PY'
import json, os, statistics, subprocess, sys
avenues, runs, model = sys.argv[1], int(sys.argv[2]), sys.argv[3]
out = [json.loads(subprocess.run([avenues, "cells", model, "--json"], capture_output=True, check=True, text=True).stdout)
       for _ in range(runs)]
imp = statistics.median(r["stages"].get("assimp import", 0.0) for r in out)
sl = statistics.median(r["stages"].get("IFC to plan", 0.0) for r in out)
tot = statistics.median(r["seconds"] for r in out)
cells, named = out[0]["cells"], out[0]["named_rooms"]
print(f"| {os.path.basename(model)} | {imp:.2f} s | {sl:.2f} s | {tot - imp - sl:.2f} s | {tot:.2f} s | {tot / imp:.2f} | {cells} | {named} |")
PY
done
