"""Reading sph_run's PLY frames (binary little-endian: position, velocity, density, pressure, fluid, id)."""
import re

import numpy as np

FRAME_DTYPE = np.dtype([("p", "<f4", 3), ("v", "<f4", 3), ("rho", "<f4"), ("pr", "<f4"), ("fluid", "u1"), ("id", "<i4")])


def read_ply(path):
    """Returns (simulated time, structured array with fields p, v, rho, pr, fluid, id)."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                raise ValueError(f"{path}: not a PLY frame written by sph_run")
            header += line
        n = int(re.search(rb"element vertex (\d+)", header).group(1))
        time = float(re.search(rb"time ([-+0-9.eE]+)", header).group(1))
        return time, np.frombuffer(f.read(n * FRAME_DTYPE.itemsize), dtype=FRAME_DTYPE, count=n)
