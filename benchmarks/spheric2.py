"""SPHERIC benchmark 2, the dam break with a box obstacle (scenes/dam_break_obstacle.json), against MARIN's
water-height gauges (benchmarks/reference/spheric2_marin_water_heights.csv; Kleefsman et al. 2005).
Called by validate.py, which runs the scene; this module compares and plots."""
import csv
import os

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
GAUGES = ("H1", "H2", "H3", "H4")
GAUGE_X = {"H1": 0.496, "H2": 0.992, "H3": 1.488, "H4": 2.638}
OBSTACLE_FACE_X = 0.8245  # the box's face towards the reservoir [m]
WET = 0.02  # a gauge is reached when it first reads more than 2 cm


def read_marin():
    with open(os.path.join(HERE, "reference", "spheric2_marin_water_heights.csv")) as f:
        rows = list(csv.reader(l for l in f if l.strip() and not l.startswith("#")))
    data = np.array([[float(x) for x in r] for r in rows[1:]])
    return data[:, 0], {g: data[:, i + 1] for i, g in enumerate(GAUGES)}


def first_time_above(t, d, level):
    """The first time d exceeds level, linearly interpolated between samples; None if it never does."""
    above = np.nonzero(np.asarray(d) > level)[0]
    if len(above) == 0:
        return None
    i = above[0]
    if i == 0:
        return float(t[0])
    return float(t[i - 1] + (level - d[i - 1]) * (t[i] - t[i - 1]) / (d[i] - d[i - 1]))


def compare(m, out, plt=None, save_chart=None):
    """m: metrics.csv columns (time, depth_H1..H4, depth_box_front). Writes OUT/spheric2_gauges.csv (the
    simulated and measured depths at the measurement times) and OUT/spheric2_gauges.png; returns the errors."""
    t_exp, exp = read_marin()
    t_sim = m["time"]
    keep = t_exp <= t_sim[-1]
    t_cmp = t_exp[keep]
    result = {"simulated_seconds": float(t_sim[-1]), "gauges": {}}
    sim_at = {}
    for g in GAUGES:
        sim_at[g] = np.interp(t_cmp, t_sim, m["depth_" + g])
        err = sim_at[g] - exp[g][keep]
        result["gauges"][g] = {
            "x_m": GAUGE_X[g], "mae_m": float(np.mean(np.abs(err))), "mean_signed_error_m": float(np.mean(err)),
            "max_measured_m": float(np.max(exp[g][keep])),
            "arrival_s": first_time_above(t_sim, m["depth_" + g], WET) if g != "H4" else None,
            "arrival_measured_s": first_time_above(t_exp, exp[g], WET) if g != "H4" else None}
    if "depth_box_front" in m:
        result["water_reaches_obstacle_s"] = first_time_above(t_sim, m["depth_box_front"], WET)
    with open(os.path.join(out, "spheric2_gauges.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time_s"] + [f"sim_{g}_m" for g in GAUGES] + [f"marin_{g}_m" for g in GAUGES])
        for i, t in enumerate(t_cmp):
            w.writerow([f"{t:.5f}"] + [f"{sim_at[g][i]:.5f}" for g in GAUGES] + [f"{exp[g][keep][i]:.5f}" for g in GAUGES])
    if plt:
        fig, axes = plt.subplots(2, 2, figsize=(10, 6), sharex=True)
        for ax, g in zip(axes.flat, GAUGES):
            ax.plot(t_exp, exp[g], "k-", lw=1, label="MARIN experiment")
            ax.plot(t_sim, m["depth_" + g], "-", color="tab:blue", lw=1.2, label="SPH (this code)")
            r = result["gauges"][g]
            ax.set_title(f"{g}, x = {GAUGE_X[g]} m: MAE {100 * r['mae_m']:.1f} cm", fontsize=9)
            ax.set_xlim(0, t_sim[-1])
            ax.set_ylabel("water depth [m]")
        for ax in axes[1]:
            ax.set_xlabel("t [s]")
        axes[0, 0].legend(fontsize=8)
        save_chart(fig, os.path.join(out, "spheric2_gauges.png"))
    return result
