"""Reading sph_run's PLY frames (binary little-endian; src/common/frame_writer.h has the format)."""
import re

import numpy as np

# PLY property types and the fields they are grouped into (x y z -> p, vx vy vz -> v, ax ay az -> a).
_TYPES = {b"float": "<f4", b"uchar": "u1", b"int": "<i4"}
_GROUPS = {b"x": ("p", 0), b"y": ("p", 1), b"z": ("p", 2), b"vx": ("v", 0), b"vy": ("v", 1), b"vz": ("v", 2),
           b"ax": ("a", 0), b"ay": ("a", 1), b"az": ("a", 2), b"density": ("rho", None), b"pressure": ("pr", None)}


def _dtype(header):
    """The record type from the header's property lines, so frames with and without ax ay az age both read."""
    fields = []
    for kind, name in re.findall(rb"property (\w+) (\w+)", header):
        field, index = _GROUPS.get(name, (name.decode(), None))
        if index is None:
            fields.append((field, _TYPES[kind]))
        elif index == 0:
            fields.append((field, _TYPES[kind], 3))
    return np.dtype(fields)


def read_ply(path):
    """Returns (simulated time, structured array with fields p, v, rho, pr, fluid, id, and a, age where present)."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                raise ValueError(f"{path}: not a PLY frame written by sph_run")
            header += line
        n = int(re.search(rb"element vertex (\d+)", header).group(1))
        time = float(re.search(rb"time ([-+0-9.eE]+)", header).group(1))
        dtype = _dtype(header)
        return time, np.frombuffer(f.read(n * dtype.itemsize), dtype=dtype, count=n)
