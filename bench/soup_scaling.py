#!/usr/bin/env python3
"""How the soup BSP's cost grows with the number of faces: the k x k grids of open boxes
(bench/soup_bench.cpp, k = 4 ... 64) decomposed by the benchmark, each three times, and
their median times plotted on log-log axes beside n log n and n^2 through the smallest
reliable point (docs/soup-scaling.svg), with the table printed for docs/PERFORMANCE.md.

    python3 bench/soup_scaling.py build/bench/avenues_bench docs/soup-scaling.svg

Standard library only: the benchmark writes JSON, this turns it into an SVG.
"""
import json
import math
import statistics
import subprocess
import sys


def measure(bench):
    out = subprocess.run(
        [bench, "--benchmark_filter=soup/open-boxes-[0-9]+/bsp/", "--benchmark_repetitions=3",
         "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    runs = {}
    for b in json.loads(out)["benchmarks"]:
        if b.get("run_type") != "iteration":
            continue
        k = int(b["name"].split("/")[1].rsplit("-", 1)[1])
        runs.setdefault(k, {"triangles": b["triangles"], "cells": b["cells"], "seconds": []})
        runs[k]["seconds"].append(b["real_time"])  # the benchmark's unit is seconds
    return [(k, r["triangles"], r["cells"], statistics.median(r["seconds"])) for k, r in sorted(runs.items())]


def plot(rows, path):
    w, h, left, right, top, bottom = 640, 420, 70, 20, 30, 50
    xs = [math.log10(n) for _, n, _, _ in rows]
    ys = [math.log10(t) for _, _, _, t in rows]
    # The reference curves go through k = 8 (k = 4 takes a few milliseconds, near the timer's noise).
    k0, n0, _, t0 = rows[1] if len(rows) > 1 else rows[0]
    nlogn = [math.log10(t0 * n * math.log2(n) / (n0 * math.log2(n0))) for _, n, _, _ in rows]
    square = [math.log10(t0 * (n / n0) ** 2) for _, n, _, _ in rows]
    x_lo, x_hi = math.floor(min(xs)), math.ceil(max(xs))
    y_lo, y_hi = math.floor(min(ys + nlogn)), math.ceil(max(ys + nlogn))
    sx = lambda x: left + (x - x_lo) / (x_hi - x_lo) * (w - left - right)
    sy = lambda y: h - bottom - (y - y_lo) / (y_hi - y_lo) * (h - top - bottom)
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w / 2}" y="18" text-anchor="middle">Soup BSP on k x k open boxes: seconds against triangles (log-log)</text>']
    for e in range(x_lo, x_hi + 1):
        svg.append(f'<line x1="{sx(e)}" y1="{top}" x2="{sx(e)}" y2="{h - bottom}" stroke="#ddd"/>')
        svg.append(f'<text x="{sx(e)}" y="{h - bottom + 16}" text-anchor="middle">10^{e}</text>')
    for e in range(y_lo, y_hi + 1):
        svg.append(f'<line x1="{left}" y1="{sy(e)}" x2="{w - right}" y2="{sy(e)}" stroke="#ddd"/>')
        svg.append(f'<text x="{left - 6}" y="{sy(e) + 4}" text-anchor="end">10^{e} s</text>')
    svg.append(f'<text x="{w / 2}" y="{h - 12}" text-anchor="middle">triangles (10 k^2)</text>')

    def line(values, colour, dash=""):
        pts = " ".join(f"{sx(x):.1f},{sy(y):.1f}" for x, y in zip(xs, values) if y_lo <= y <= y_hi)
        return f'<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="2" {dash}/>'

    svg.append(line(square, "#c66", 'stroke-dasharray="2 4"'))
    svg.append(line(nlogn, "#888", 'stroke-dasharray="6 4"'))
    svg.append(line(ys, "#236"))
    for (k, n, cells, t), x, y in zip(rows, xs, ys):
        svg.append(f'<circle cx="{sx(x):.1f}" cy="{sy(y):.1f}" r="4" fill="#236"/>')
        svg.append(f'<text x="{sx(x) + 6:.1f}" y="{sy(y) - 6:.1f}">k={k}</text>')
    legend = [("#236", "measured (median of 3)"), ("#888", "n log n through k = 8"), ("#c66", "n^2 through k = 8")]
    for i, (colour, text) in enumerate(legend):
        y = top + 14 + 16 * i
        svg.append(f'<line x1="{left + 10}" y1="{y - 4}" x2="{left + 34}" y2="{y - 4}" stroke="{colour}" stroke-width="2"/>')
        svg.append(f'<text x="{left + 40}" y="{y}">{text}</text>')
    svg.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(svg) + "\n")


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: soup_scaling.py AVENUES_BENCH OUT.svg")
    rows = measure(sys.argv[1])
    if not rows:
        sys.exit("soup_scaling.py: the benchmark ran no open-box grid")
    plot(rows, sys.argv[2])
    print("| k | triangles | cells | median | µs per triangle | per triangle / log2 n, against k = 8 |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: |")
    n0, t0 = rows[min(1, len(rows) - 1)][1], rows[min(1, len(rows) - 1)][3]
    base = t0 / n0 / math.log2(n0)
    for k, n, cells, t in rows:
        print(f"| {k} | {int(n):,} | {int(cells):,} | {t:.3f} s | {1e6 * t / n:.0f} | {t / n / math.log2(n) / base:.2f} |")


if __name__ == "__main__":
    main()
