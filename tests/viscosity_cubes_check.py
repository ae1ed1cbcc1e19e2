#!/usr/bin/env python3
"""scenes/viscosity_cubes.json must show what it claims (issue 10): at 0.4 s, 0.25 s after landing, the
thin fluid has spread across the tank, the middle one is a pancake and the most viscous one still a block.
Runs sph_run (8 particles across a cube, to be quick; 10 in the scene gives the same picture) and measures
each fluid's height (98th percentile of y above the floor) and width along x (2nd to 98th percentile).

usage: viscosity_cubes_check.py SPH_RUN SCENE OUT_DIR [SPH_RUN OPTION ...] (for example --set solver=pbf)"""
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks"))
import numpy as np  # noqa: E402
from ply_frames import read_ply  # noqa: E402


def shape(frame):
    """(height, width) of each fluid in a PLY frame."""
    _, a = read_ply(frame)
    out = []
    for f in range(3):
        p = a["p"][a["fluid"] == f]
        out.append((np.percentile(p[:, 1], 98), np.percentile(p[:, 0], 98) - np.percentile(p[:, 0], 2)))
    return out


def main():
    sph_run, scene, out = sys.argv[1:4]
    extra = sys.argv[4:]
    shutil.rmtree(out, ignore_errors=True)
    subprocess.run([sph_run, scene, "--backend", "cpu", "--time", "0.4", "--frames-every", "0.4", "--quiet",
                    "--set", "resolution.particles_across=8", "--out", out] + extra, check=True)
    start, end = shape(os.path.join(out, "frame_00000.ply")), shape(os.path.join(out, "frame_00001.ply"))
    h0 = start[0][0] - 0.1  # the cubes start 0.1 m above the floor
    w0 = start[0][1]
    failed = []
    for name, (h, w) in zip(("thin", "honey", "paste"), end):
        print(f"{name}: height {h:.3f} m ({h / h0:.0%} of the cube's), width {w:.3f} m ({w / w0:.2f} times the cube's)")
    (_, w_thin), (h_honey, w_honey), (h_paste, w_paste) = end
    if not w_thin > 2.5 * w0:
        failed.append("the thin fluid has not spread across the tank")
    if not (h_honey < 0.5 * h0 and w_honey > 1.4 * w0):
        failed.append("the 10 Pa s cube has not spread into a pancake")
    if not (h_paste > 0.6 * h0 and w_paste < 1.3 * w0):
        failed.append("the 300 Pa s cube has not kept its shape")
    if not h_paste > 1.8 * h_honey:
        failed.append("the 300 Pa s cube is not clearly taller than the 10 Pa s one")
    for f in failed:
        print("FAILED:", f)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
