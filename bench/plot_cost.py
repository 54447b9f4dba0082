#!/usr/bin/python3
"""The price of exactness as pictures: time per ray against wrong rays per million, one point per
kernel, for N = 1, 5 and all hits.

Reads either JSON Pierce writes:
  build/bin/pierce_bench_kernels --json bench.json        (every scene, reference rows of plain Embree)
  build/bin/pierce hits MODEL --rays R --kernel all --json hits.json   (your model, one N)
and writes one PNG per scene (or one for the hits table):

  /usr/bin/python3 bench/plot_cost.py bench.json --out cost      ->  cost_<scene>.png
  /usr/bin/python3 bench/plot_cost.py hits.json --out cost       ->  cost_hits.png

Exact kernels sit on the zero line; the further right, the more the exactness costs. Needs
python3-matplotlib (Debian).
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = [1, 5, "all"]


def bench_points(scene):
    """{N: [(kernel, ns_per_ray, wrong_per_million, exact)]} from one bench scene."""
    rays = scene["rays"]
    out = {n: [] for n in COLUMNS}
    for row in scene["rows"]:
        for cell in row["cells"]:
            n = cell["max_hits"]
            if n not in out:
                continue
            ns = cell["median_seconds"] * 1e9 / rays
            wrong = 0 if row["exact"] else cell.get("wrong_rays", 0)
            out[n].append((row["kernel"], ns, wrong * 1e6 / rays, row["exact"]))
    return out


def hits_points(table):
    rays = table["rays"]
    pts = [(k["kernel"], k["ns_per_ray"], k["rays_differ"] * 1e6 / rays, k["exact"]) for k in table["kernels"]]
    return {table["max_hits"]: pts}


def label_offsets(ax, points, fontsize):
    """Offsets (in points) for the points' labels, so that no two labels overlap: kernels of
    about the same time and the same error rate sit on top of each other, and their names did.
    Greedy, left to right: each label takes the first offset, going up from the point and then
    down, whose box clears every label placed so far."""
    to_points = 72.0 / ax.figure.dpi
    char_w, line_h = 0.6 * fontsize, 1.25 * fontsize
    candidates = [(4, 4 + k * line_h) for k in range(8)] + [(4, -4 - (k + 1) * line_h) for k in range(4)]
    placed = []  # label boxes (x0, y0, x1, y1) in points
    offsets = {}
    order = sorted(range(len(points)), key=lambda i: points[i][1])
    for i in order:
        kernel, ns, wrong = points[i][:3]
        px, py = (v * to_points for v in ax.transData.transform((ns, wrong)))
        width = char_w * len(kernel)
        choice = candidates[0]
        for dx, dy in candidates:
            box = (px + dx, py + dy, px + dx + width, py + dy + line_h)
            if all(box[2] <= b[0] or b[2] <= box[0] or box[3] <= b[1] or b[3] <= box[1] for b in placed):
                choice = (dx, dy)
                break
        placed.append((px + choice[0], py + choice[1], px + choice[0] + width, py + choice[1] + line_h))
        offsets[i] = choice
    return offsets


def draw(title, columns, path, ylabel="wrong rays per million"):
    cols = [n for n in columns if columns[n]]
    fig, axes = plt.subplots(1, len(cols), figsize=(5.2 * len(cols), 4.4), squeeze=False)
    for ax, n in zip(axes[0], cols):
        for kernel, ns, wrong, exact in columns[n]:
            ref = kernel.startswith("embree ")
            ax.scatter([ns], [wrong], marker="s" if ref else ("o" if exact else "x"),
                       color="tab:gray" if ref else ("tab:blue" if exact else "tab:red"), zorder=3)
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=1.0)
        # Room above the highest point and right of the slowest for their labels.
        ns_min = min(p[1] for p in columns[n])
        ns_max = max(p[1] for p in columns[n])
        if ns_min > 0:  # a cell too quick to time has no place on a log axis
            ax.set_xlim(ns_min / 1.15, ns_max * 1.8)
        ax.set_ylim(bottom=-0.3, top=max(10.0, max(p[2] for p in columns[n])) * 30)
        ax.set_xlabel("time per ray (ns, log)")
        ax.set_ylabel(ylabel)
        ax.set_title(f"N = {n}")
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle(title + "\nblue: exact, red: inexact Pierce kernel, grey: plain Embree code", fontsize=9)
    fig.tight_layout()
    # Labels last: their overlaps are judged where tight_layout() put the axes.
    for ax, n in zip(axes[0], cols):
        offsets = label_offsets(ax, columns[n], fontsize=7)
        for i, (kernel, ns, wrong, _) in enumerate(columns[n]):
            ax.annotate(kernel, (ns, wrong), textcoords="offset points", xytext=offsets[i], fontsize=7,
                        arrowprops=dict(arrowstyle="-", color="0.6", lw=0.5) if offsets[i][1] > 10 or offsets[i][1] < 0 else None)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("json", help="pierce_bench_kernels --json or pierce hits --kernel all --json output")
    ap.add_argument("--out", default="cost", help="prefix of the PNG files (default: cost)")
    ap.add_argument("--force", action="store_true", help="overwrite existing PNG files")
    args = ap.parse_args()
    try:
        with open(args.json) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_cost.py: {args.json}: {e}")

    if "scenes" in data:
        jobs = [(f"{s['name']}: {s['triangles']} triangles, {s['rays']} rays", bench_points(s),
                 f"{args.out}_{s['name']}.png", "wrong rays per million (hit list not the exact one)")
                for s in data["scenes"]]
    elif data.get("source") == "pierce hits --kernel all":
        jobs = [(f"pierce hits --kernel all: {data['rays']} rays", hits_points(data), f"{args.out}_hits.png",
                 "rays per million differing\nfrom the exact consensus (t included)")]
    else:
        sys.exit(f"plot_cost.py: {args.json}: neither a pierce_bench_kernels nor a pierce hits --json file")
    for _, _, path, _ in jobs:
        if os.path.exists(path) and not args.force:
            sys.exit(f"plot_cost.py: {path} exists; pass --force to overwrite it")
    for title, columns, path, ylabel in jobs:
        draw(title, columns, path, ylabel)


if __name__ == "__main__":
    main()
