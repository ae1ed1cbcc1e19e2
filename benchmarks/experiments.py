"""Errors against the reference data in ../shared/reference-data, one definition for validate.py and
studies.py: Martin & Moyce's (1952) dam break and the thesis's water-jet range."""
import csv
import math
import os

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE = os.path.join(os.path.dirname(ROOT), "shared", "reference-data")
A = 0.05715  # Martin & Moyce column width [m]
G = 9.81
AXIM_RANGE = 3.97  # thesis 5.1: the AXIM model's jet range [m]


def read_reference(name):
    with open(os.path.join(REFERENCE, name)) as f:
        lines = [l for l in f if l.strip() and not l.startswith("#")]
    rows = list(csv.reader(lines))
    return np.array([[float(x) for x in r] for r in rows[1:]])


def dam_break_curves(time, front_x, height_at_x0):
    """Martin & Moyce's dimensionless variables: T = t sqrt(2g/a), Z = x/a, tau = t sqrt(g/a), H = y/(2a)."""
    time = np.asarray(time, dtype=float)
    return (time * math.sqrt(2 * G / A), np.asarray(front_x, dtype=float) / A, time * math.sqrt(G / A),
            np.asarray(height_at_x0, dtype=float) / (2 * A))


def dam_break_errors(time, front_x, height_at_x0):
    """Surge front over T <= 3 and column height, at the experiment's points within the run."""
    T, Z, tau, H = dam_break_curves(time, front_x, height_at_x0)
    surge = read_reference("martin_moyce_1952_surge_front.csv")
    column = read_reference("martin_moyce_1952_column_height.csv")
    surge = surge[(surge[:, 0] <= 3.0) & (surge[:, 0] <= T[-1])]
    column = column[column[:, 0] <= tau[-1]]
    dz = np.interp(surge[:, 0], T, Z) - surge[:, 1]
    dh = np.interp(column[:, 0], tau, H) - column[:, 1]
    return {"surge_front_mae_T_le_3": float(np.mean(np.abs(dz))), "surge_points": len(surge),
            "surge_front_mean_signed_error": float(np.mean(dz)),
            "column_height_mae": float(np.mean(np.abs(dh))) if len(column) else None, "column_points": len(column)}


def jet_range(time, front_x):
    """Median front position once the jet has landed (the first particles land after about 0.85 s)."""
    landed = np.asarray(time, dtype=float) > 1.0
    return float(np.median(np.asarray(front_x, dtype=float)[landed])) if landed.any() else float("nan")
