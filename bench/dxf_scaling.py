#!/usr/bin/env python3
"""How reading a DXF floor plan grows with the drawing: k x k rooms of 4 m in walls drawn as
double lines 0.2 m apart (R12 LINEs on A-WALL, the outer walls whole), a door gap in every
inner wall of every room with its swing on A-DOOR and the jamb caps drawn, a name in every
room; with --leaves, each door's leaf and two frame lines across the wall too (door lines
that are not swings, which the search for doors drawn without a swing looks through). Each drawing is read by `avenues cells` (each binary given, in turn, `runs` times) and
the `read drawing` stage and the total are printed as a table for docs/PERFORMANCE.md, with
what the reader understood. Several binaries are run alternately, as peers in one script.

    python3 bench/dxf_scaling.py [--runs N] [--k 10,30,60,100] [--leaves] AVENUES [AVENUES ...]

Standard library only; the drawings go to a temporary folder.
"""
import argparse
import os
import re
import statistics
import subprocess
import tempfile

S, T = 4.0, 0.1  # room size, half the wall's thickness [m]


def line(layer, a, b):
    return ["0", "LINE", "8", layer, "10", repr(a[0]), "20", repr(a[1]), "30", "0",
            "11", repr(b[0]), "21", repr(b[1]), "31", "0"]


def arc(layer, c, r, a0, a1):
    return ["0", "ARC", "8", layer, "10", repr(c[0]), "20", repr(c[1]), "30", "0", "40", repr(r),
            "50", repr(a0), "51", repr(a1)]


def wall(e, vertical, at, lo, hi, gaps, leaves):
    """A wall's two faces from lo to hi along it, cut at each gap (capped, with a swing)."""
    def pt(along, across):
        return (across, along) if vertical else (along, across)
    stops = [lo] + [v for g in gaps for v in g] + [hi]
    for k in range(0, len(stops), 2):
        for side in (-T, T):
            e.append(line("A-WALL", pt(stops[k], at + side), pt(stops[k + 1], at + side)))
    for g0, g1 in gaps:
        for v in (g0, g1):
            e.append(line("A-WALL", pt(v, at - T), pt(v, at + T)))
        if vertical:
            e.append(arc("A-DOOR", (at - T, g0), g1 - g0, 90, 180))
        else:
            e.append(arc("A-DOOR", (g0, at + T), g1 - g0, 0, 90))
        if leaves:
            hinge = pt(g0, at - T) if vertical else pt(g0, at + T)
            e.append(line("A-DOOR", hinge, pt(g0, at - T - (g1 - g0)) if vertical else pt(g0, at + T + (g1 - g0))))
            for v in (g0 + 0.05, g1 - 0.05):
                e.append(line("A-DOOR", pt(v, at - T), pt(v, at + T)))


def drawing(k, leaves):
    e = []
    for i in range(k + 1):
        gaps = [] if i in (0, k) else [(S * j + 1.5, S * j + 2.4) for j in range(k)]
        wall(e, True, S * i, -T, S * k + T, gaps, leaves)
        wall(e, False, S * i, -T, S * k + T, gaps, leaves)
    for i in range(k):
        for j in range(k):
            e.append(["0", "TEXT", "8", "Text", "10", repr(S * i + 2), "20", repr(S * j + 3), "30", "0",
                      "40", "0.2", "1", "R%d_%d" % (i, j)])
    out = ["0", "SECTION", "2", "HEADER", "9", "$INSUNITS", "70", "6", "0", "ENDSEC",
           "0", "SECTION", "2", "ENTITIES"]
    for x in e:
        out += x
    out += ["0", "ENDSEC", "0", "EOF"]
    return "\n".join(out) + "\n"


def read(avenues, path):
    out = subprocess.run([avenues, "cells", path], capture_output=True, text=True, check=True)
    said = out.stderr + out.stdout
    stage = float(re.search(r"read drawing ([0-9.]+)", said).group(1))
    total = float(re.search(r"total ([0-9.]+)", said).group(1))
    understood = re.search(r"(\d+ walls, \d+ doors, \d+ windows, \d+ rooms)", said).group(1)
    return stage, total, understood


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--k", default="10,30,60,100")
    ap.add_argument("--leaves", action="store_true")
    ap.add_argument("avenues", nargs="+")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        print("| rooms | binary | understood | read drawing (median) | total (median) |")
        print("| ---: | --- | --- | ---: | ---: |")
        for k in [int(v) for v in args.k.split(",")]:
            path = os.path.join(tmp, "grid%d.dxf" % k)
            with open(path, "w") as f:
                f.write(drawing(k, args.leaves))
            times = {b: [] for b in args.avenues}
            said = {}
            for _ in range(args.runs):
                for b in args.avenues:
                    stage, total, said[b] = read(b, path)
                    times[b].append((stage, total))
            for b in args.avenues:
                st = statistics.median(t[0] for t in times[b])
                to = statistics.median(t[1] for t in times[b])
                print("| %d | %s | %s | %.3f s | %.3f s |" % (k * k, b, said[b], st, to))


if __name__ == "__main__":
    main()
