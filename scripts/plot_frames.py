#!/usr/bin/python3
"""Side views of sph_run's PLY frames, coloured by speed: a quick look at a run without a renderer.

usage: scripts/plot_frames.py OUT_DIR --times 0 0.1 0.2 --out picture.png [--axes xy]
Needs Debian's python3-matplotlib (apt-get install python3-matplotlib).
"""
import argparse
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "benchmarks"))
from ply_frames import read_ply  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out_dir")
    ap.add_argument("--times", type=float, nargs="+", required=True, help="simulated times to show (nearest frame)")
    ap.add_argument("--out", required=True, help="PNG to write")
    ap.add_argument("--axes", default="xy", choices=["xy", "xz", "zy"])
    args = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = sorted(glob.glob(os.path.join(args.out_dir, "frame_*.ply")))
    if not paths:
        sys.exit(f"error: no frame_*.ply in {args.out_dir} (run sph_run with --frames-every)")
    frames = [read_ply(p) for p in paths]
    ia, ib = "xyz".index(args.axes[0]), "xyz".index(args.axes[1])
    picks = [min(frames, key=lambda f: abs(f[0] - t)) for t in args.times]
    lo = np.min([f[1]["p"].min(axis=0) for f in picks], axis=0)
    hi = np.max([f[1]["p"].max(axis=0) for f in picks], axis=0)
    vmax = max(float(np.linalg.norm(f[1]["v"], axis=1).max()) for f in picks) or 1.0
    cols = min(2, len(picks))
    rows = (len(picks) + cols - 1) // cols
    aspect = (hi[ib] - lo[ib]) / max(hi[ia] - lo[ia], 1e-9)
    fig, axes = plt.subplots(rows, cols, figsize=(4.5 * cols, 4.5 * rows * aspect + 0.8), squeeze=False)
    for ax in axes.flat[len(picks):]:
        ax.axis("off")
    for ax, (time, d) in zip(axes.flat, picks):
        speed = np.linalg.norm(d["v"], axis=1)
        order = np.argsort(d["p"][:, 3 - ia - ib])  # draw far particles first
        sc = ax.scatter(d["p"][order, ia], d["p"][order, ib], c=speed[order], s=1.0, cmap="viridis", vmin=0, vmax=vmax)
        ax.set_xlim(lo[ia], hi[ia])
        ax.set_ylim(lo[ib], hi[ib])
        ax.set_aspect("equal")
        ax.set_title(f"t = {time:.3f} s", fontsize=9)
        ax.tick_params(labelsize=7)
    fig.colorbar(sc, ax=axes.ravel().tolist(), label="speed [m/s]", shrink=0.8)
    fig.savefig(args.out, dpi=130, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
