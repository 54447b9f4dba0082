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


def draw(title, columns, path, ylabel="wrong rays per million"):
    cols = [n for n in columns if columns[n]]
    fig, axes = plt.subplots(1, len(cols), figsize=(5.2 * len(cols), 4.4), squeeze=False)
    for ax, n in zip(axes[0], cols):
        for kernel, ns, wrong, exact in columns[n]:
            ref = kernel.startswith("embree ")
            ax.scatter([ns], [wrong], marker="s" if ref else ("o" if exact else "x"),
                       color="tab:gray" if ref else ("tab:blue" if exact else "tab:red"), zorder=3)
            ax.annotate(kernel, (ns, wrong), textcoords="offset points", xytext=(4, 4), fontsize=7)
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=1.0)
        ax.set_ylim(bottom=-0.3)
        ax.set_xlabel("time per ray (ns, log)")
        ax.set_ylabel(ylabel)
        ax.set_title(f"N = {n}")
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle(title + "   (blue: exact, red: inexact Pierce kernel, grey: plain Embree code)", fontsize=9)
    fig.tight_layout()
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
                 "rays per million differing from the exact consensus (t included)")]
    else:
        sys.exit(f"plot_cost.py: {args.json}: neither a pierce_bench_kernels nor a pierce hits --json file")
    for _, _, path, _ in jobs:
        if os.path.exists(path) and not args.force:
            sys.exit(f"plot_cost.py: {path} exists; pass --force to overwrite it")
    for title, columns, path, ylabel in jobs:
        draw(title, columns, path, ylabel)


if __name__ == "__main__":
    main()
