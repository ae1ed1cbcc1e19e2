#!/usr/bin/python3
"""A shaded 3-D view of surface meshes that sph_run --surface-every or sph_surface wrote (binary PLY), with
matplotlib alone: a look at the exported surface without Blender or ParaView.

usage: scripts/plot_surface.py OUT/surface_00002.ply [more meshes side by side] --out picture.png
Needs Debian's python3-matplotlib and python3-numpy: run it as scripts/plot_surface.py (its first line names
/usr/bin/python3), not with another python3 that lacks them.
"""
import argparse
import sys

import numpy as np


def read_mesh(path):
    """Vertices (n x 3 float) and triangles (m x 3 int) of a binary little-endian PLY mesh, and its time."""
    try:
        f = open(path, "rb")
    except OSError as e:
        sys.exit(f"error: {path}: {e.strerror}")
    with f:
        header, counts, time = [], {}, None
        while True:
            line = f.readline()
            if not line:
                sys.exit(f"error: {path}: the header has no end_header line")
            text = line.decode("ascii", "replace").strip()
            header.append(text)
            if text.startswith("element"):
                _, name, n = text.split()
                counts[name] = int(n)
            elif text.startswith("comment time"):
                time = float(text.split()[2])
            elif text == "end_header":
                break
        if "format binary_little_endian 1.0" not in header or "vertex" not in counts or "face" not in counts:
            sys.exit(f"error: {path}: not a binary PLY mesh of vertices and faces as sph_surface writes them")
        vertices = np.frombuffer(f.read(12 * counts["vertex"]), dtype="<f4").reshape(-1, 3)
        faces = np.frombuffer(f.read(13 * counts["face"]), dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]))
        if len(vertices) != counts["vertex"] or len(faces) != counts["face"] or np.any(faces["n"] != 3):
            sys.exit(f"error: {path}: the file is shorter than its header says, or has faces that are not triangles")
    if len(faces) == 0:
        sys.exit(f"error: {path}: the mesh has no triangles (a frame without fluid)")
    return vertices, faces["i"], time


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--out", required=True, help="PNG to write")
    args = ap.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    fig = plt.figure(figsize=(5.5 * len(args.meshes), 4.5))
    light = np.array([0.45, 0.8, -0.6])  # from above and the camera's side (+x, -z: azimuth -60 degrees)
    light /= np.linalg.norm(light)
    for k, path in enumerate(args.meshes):
        v, t, time = read_mesh(path)
        tri = v[t]  # m x 3 x 3
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-30)
        shade = 0.35 + 0.65 * np.clip(n @ light, 0.0, 1.0)
        colours = np.outer(shade, [0.25, 0.55, 0.9])
        ax = fig.add_subplot(1, len(args.meshes), k + 1, projection="3d")
        # the simulation's y is up: draw x, z, y
        ax.add_collection3d(Poly3DCollection(tri[:, :, [0, 2, 1]], facecolors=colours, linewidths=0))
        lo, hi = v.min(axis=0), v.max(axis=0)
        ax.set_xlim(lo[0], hi[0]), ax.set_ylim(lo[2], hi[2]), ax.set_zlim(lo[1], hi[1])
        ax.set_box_aspect((hi[0] - lo[0], hi[2] - lo[2], hi[1] - lo[1]))
        ax.view_init(elev=25, azim=-60)
        ax.set_xlabel("x [m]"), ax.set_ylabel("z [m]"), ax.set_zlabel("y [m]")
        ax.set_title(f"{path.split('/')[-1]}" + (f", t = {time:.2f} s" if time is not None else "") + f"\n{len(t)} triangles", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
