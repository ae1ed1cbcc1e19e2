#!/usr/bin/python3
"""A slice through sph_run's PLY frames: the particles within half a spacing of a plane through the fluid's
centre, coloured by fluid and by pressure, and the pressure against the distance from the centre of one
fluid (Laplace's jumps of a drop, or of a drop within a drop, read off as steps).

usage: scripts/plot_slice.py OUT_DIR [OUT_DIR ...] --times 0 1 --out picture.png [--spacing 0.004]
       [--centre-fluid 0] [--laplace PA ...] [--labels NAME ...]
       (a row per folder and time; --laplace: horizontal lines at these pressures, for comparison)
Needs Debian's python3-matplotlib (apt-get install python3-matplotlib).
"""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "benchmarks"))
from ply_frames import read_ply  # noqa: E402


def nearest_frame(paths, t):
    times = [read_ply(p)[0] for p in paths]
    return paths[int(np.argmin([abs(x - t) for x in times]))]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dirs", nargs="+", metavar="OUT_DIR")
    ap.add_argument("--times", type=float, nargs="+", required=True, help="simulated times to show (nearest frame)")
    ap.add_argument("--out", required=True, help="PNG to write")
    ap.add_argument("--spacing", type=float, default=0.004, help="particle spacing [m]: the slice's thickness")
    ap.add_argument("--centre-fluid", type=int, default=0, help="the fluid whose centre the profile is taken from")
    ap.add_argument("--laplace", type=float, nargs="*", default=[], help="pressures [Pa] drawn as dashed lines")
    ap.add_argument("--labels", nargs="*", default=[], help="a name per OUT_DIR for the rows' titles")
    args = ap.parse_args()
    if args.labels and len(args.labels) != len(args.out_dirs):
        sys.exit(f"--labels: {len(args.labels)} names for {len(args.out_dirs)} folders")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = []
    for k, out_dir in enumerate(args.out_dirs):
        paths = sorted(glob.glob(os.path.join(out_dir, "frame_*.ply")))
        if not paths:
            sys.exit(f"{out_dir}: no frame_*.ply files (run sph_run with --out {out_dir} first)")
        rows += [(paths, args.labels[k] + ", " if args.labels else "", t) for t in args.times]
    fig, axes = plt.subplots(len(rows), 3, figsize=(13, 4.2 * len(rows)), squeeze=False)
    colours = np.array(["tab:orange", "tab:blue", "tab:green", "tab:red", "tab:purple", "tab:brown", "tab:pink", "tab:gray"])
    for row, (paths, label, t) in zip(axes, rows):
        time, a = read_ply(nearest_frame(paths, t))
        p = a["p"].astype(float)
        fluid = a["fluid"].astype(int)
        mine = fluid == args.centre_fluid
        centre = p[mine].mean(axis=0) if mine.any() else p.mean(axis=0)
        cut = np.abs(p[:, 2] - centre[2]) < 0.5 * args.spacing
        row[0].scatter(p[cut, 0], p[cut, 1], s=6, c=colours[fluid[cut] % len(colours)])
        row[0].set_title(f"{label}t = {time:.2f} s: fluids, slice z = {round(float(centre[2]), 3) + 0.0:.3f} m")
        sc = row[1].scatter(p[cut, 0], p[cut, 1], s=6, c=a["pr"][cut], cmap="viridis")
        fig.colorbar(sc, ax=row[1], label="pressure [Pa]")
        row[1].set_title("pressure")
        for ax in row[:2]:
            ax.set_aspect("equal")
            ax.set_xlabel("x [m]")
            ax.set_ylabel("y [m]")
        r = np.linalg.norm(p - centre, axis=1)
        for f in np.unique(fluid):
            sel = fluid == f
            row[2].scatter(r[sel], a["pr"][sel], s=2, alpha=0.4, color=colours[f % len(colours)], label=f"fluid {f}")
        for level in args.laplace:
            row[2].axhline(level, color="k", linestyle="--", linewidth=1)
        row[2].set_xlabel(f"distance from fluid {args.centre_fluid}'s centre [m]")
        row[2].set_ylabel("pressure [Pa]")
        row[2].legend(markerscale=4)
        row[2].set_title("pressure against radius" + (" (dashed: Laplace)" if args.laplace else ""))
    fig.tight_layout()
    fig.savefig(args.out, dpi=80)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
