#!/usr/bin/python3
"""Studies behind the charts: where each method becomes unstable, how much tensile clustering near
pressure prevents, and accuracy against cost. Runs build/sph_run and writes CSV files and PNG charts.

  stability map    largest stable fixed time step on the dam break, per integrator, for the two ways of
                   handling tensile instability (clamped pressure; negative pressure kept + near
                   pressure), with Tait and ideal equations of state (bisection on dt); stable = no
                   blow-up, no runaway speed, mean density within 10% of rest density
  clustering       zero-g drop with and without near pressure: smallest pair distance, clustered share
  accuracy-cost    dam-break surge-front error and water-jet range error against wall time per simulated
                   second, one point per back end and resolution; Pareto front marked
  scaling          ms per step against particles, per back end (from sph_bench's bench.csv, if given)

usage: benchmarks/studies.py [--quick] [--out out/studies] [--bench out/bench/bench.csv]
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

from ply_frames import read_ply

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REFERENCE = os.path.join(os.path.dirname(ROOT), "shared", "reference-data")
A, G = 0.05715, 9.81
INTEGRATORS = ["explicit_euler", "semi_implicit_euler", "velocity_verlet", "modified_velocity_verlet", "leapfrog"]
VARIANTS = {"clamp": ["sph.negative_pressure=clamp", "fluids.0.near_stiffness=0"],
            "keep+near": ["sph.negative_pressure=keep", "fluids.0.near_stiffness=4"]}


def sph_run(build, scene, t, out, sets, backend="host", frames_every=0.0, metrics_every=0.005):
    cmd = [os.path.join(build, "sph_run"), os.path.join(ROOT, "scenes", scene), "--backend", backend, "--time", str(t),
           "--out", out, "--frames-every", str(frames_every), "--metrics-every", str(metrics_every), "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode not in (0, 3):
        sys.exit(f"error: {' '.join(cmd)}\n{p.stderr}")
    summary = dict(re.findall(r"^(\w+): (.*)$", p.stdout, re.M))
    rows = []
    mpath = os.path.join(out, "metrics.csv")
    if os.path.exists(mpath):
        with open(mpath) as f:
            rows = list(csv.DictReader(f))
    return p.returncode, summary, rows, wall


def stability_map(args, out):
    rows = []
    integrators = INTEGRATORS[:2] if args.quick else INTEGRATORS
    variants = ["clamp"] if args.quick else list(VARIANTS)
    eoses = ["tait"] if args.quick else ["tait", "ideal"]
    iterations = 2 if args.quick else 6
    t_run = 0.05 if args.quick else 0.1
    for integ in integrators:
        for var in variants:
            for eos in eoses:
                base = ["resolution.particles_across=12", f"integrator={integ}", f"sph.equation_of_state={eos}",
                        "time_step.mode=fixed"] + VARIANTS[var]

                def stable(dt):
                    rc, _, m, _ = sph_run(args.build, "dam_break.json", t_run, os.path.join(out, "stab_run"),
                                          base + [f"time_step.dt={dt}"])
                    if rc != 0 or not m:
                        return False
                    # No runaway below the blow-up bound, and still a liquid: mean density within 10% of rho0.
                    return (float(m[-1]["v_max"]) < 5.0 * math.sqrt(2 * G * 2 * A) and
                            float(m[-1]["density_error_mean"]) < 0.10)

                lo, hi = 1e-5, 4e-3  # 6 bisections in log space: the answer is within about 10%
                if not stable(lo):
                    best = 0.0
                elif stable(hi):
                    best = hi
                else:
                    for _ in range(iterations):
                        mid = math.sqrt(lo * hi)
                        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
                    best = lo
                print(f"  stability: {integ:26s} {var:10s} {eos:6s} largest stable dt {best:.2e} s", flush=True)
                rows.append({"integrator": integ, "variant": var, "eos": eos, "largest_stable_dt": best,
                             "simulated_seconds": t_run})
    write_csv(os.path.join(out, "stability_map.csv"), rows)
    return rows


def clustering(args, out):
    rows = []
    for k in (0.0, 0.5):
        d = os.path.join(out, f"drop_near_{k}")
        sph_run(args.build, "drop_zero_g.json", 0.5, d, [f"fluids.0.near_stiffness={k}"], frames_every=0.5)
        frames = sorted(f for f in os.listdir(d) if f.startswith("frame_"))
        p = read_ply(os.path.join(d, frames[-1]))[1]["p"].astype(np.float64)
        dist = np.sqrt(((p[:, None, :] - p[None, :, :]) ** 2).sum(-1))
        np.fill_diagonal(dist, np.inf)
        spacing = 0.1 / 12
        nearest = dist.min(axis=1)
        rows.append({"near_stiffness": k, "min_pair_distance_over_spacing": float(nearest.min() / spacing),
                     "clustered_share_below_half_spacing": float(np.mean(nearest < 0.5 * spacing))})
        print(f"  clustering: near_stiffness {k}: min pair distance {nearest.min() / spacing:.3f} d, "
              f"clustered {100 * np.mean(nearest < 0.5 * spacing):.1f}%", flush=True)
    write_csv(os.path.join(out, "clustering.csv"), rows)
    return rows


def surge_error(rows):
    t = np.array([float(r["time"]) for r in rows])
    T, Z = t * math.sqrt(2 * G / A), np.array([float(r["front_x"]) for r in rows]) / A
    with open(os.path.join(REFERENCE, "martin_moyce_1952_surge_front.csv")) as f:
        ref = np.array([[float(x) for x in l.split(",")] for l in f if l[0].isdigit()])
    ref = ref[(ref[:, 0] <= 3.0) & (ref[:, 0] <= T[-1])]
    return float(np.mean(np.abs(np.interp(ref[:, 0], T, Z) - ref[:, 1])))


def accuracy_cost(args, out):
    rows = []
    backends = ["cpu", "host"]
    sizes = [10] if args.quick else [12, 16, 20, 26]
    t_end = 0.17  # T = 3.15
    for n in sizes:
        for b in backends:
            rc, s, m, wall = sph_run(args.build, "dam_break.json", t_end, os.path.join(out, "acc_run"),
                                     [f"resolution.particles_across={n}"], backend=b, metrics_every=0.002)
            if rc != 0:
                continue
            rows.append({"case": "dam_break", "backend": b, "resolution": n, "particles": int(s["particles"]),
                         "wall_per_simulated_second": wall / float(s["simulated_time"]), "error": surge_error(m)})
            print(f"  accuracy-cost: dam break {n:3d} across on {b:4s}: {rows[-1]['particles']} particles, "
                  f"error {rows[-1]['error']:.3f}, {rows[-1]['wall_per_simulated_second']:.0f} s per simulated s", flush=True)
    jet_sizes = [6] if args.quick else [7, 10, 13]
    for n in jet_sizes:
        rc, s, m, wall = sph_run(args.build, "water_jet.json", 1.2, os.path.join(out, "acc_run"),
                                 [f"resolution.particles_across={n}"], backend="host", metrics_every=0.01)
        if rc != 0:
            continue
        landed = [float(r["front_x"]) for r in m if float(r["time"]) > 1.0]
        rng = float(np.median(landed))
        rows.append({"case": "water_jet", "backend": "host", "resolution": n, "particles": int(s["particles"]),
                     "wall_per_simulated_second": wall / float(s["simulated_time"]), "error": abs(rng - 3.97) / 3.97})
        print(f"  accuracy-cost: water jet {n} across: range {rng:.3f} m, error {100 * rows[-1]['error']:.1f}%", flush=True)
    write_csv(os.path.join(out, "accuracy_cost.csv"), rows)
    return rows


def write_csv(path, rows):
    if not rows:
        return
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def pareto(points):
    """Indices of points not beaten in both cost and error by another point."""
    keep = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for j, (c2, e2) in enumerate(points) if j != i):
            keep.append(i)
    return sorted(keep, key=lambda i: points[i][0])


def charts(out, stab, acc, bench):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if stab:
        fig, ax = plt.subplots(figsize=(9, 3.8))
        combos = sorted({(r["variant"], r["eos"]) for r in stab})
        integs = [i for i in INTEGRATORS if any(r["integrator"] == i for r in stab)]
        width = 0.8 / len(combos)
        for k, (var, eos) in enumerate(combos):
            vals = [next((r["largest_stable_dt"] for r in stab if r["integrator"] == i and r["variant"] == var and r["eos"] == eos), 0)
                    for i in integs]
            ax.bar(np.arange(len(integs)) + k * width, [v * 1e3 for v in vals], width, label=f"{var}, {eos}")
        ax.set_xticks(np.arange(len(integs)) + 0.4 - width / 2)
        ax.set_xticklabels([i.replace("_", " ") for i in integs], fontsize=8)
        ax.set_ylabel("largest stable dt [ms]")
        ax.set_title(f"Dam break (12 particles across a), fixed time step, {stab[0]['simulated_seconds']} s simulated")
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "stability_map.png"), dpi=120)
    if acc:
        fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
        for ax, case, label in ((axes[0], "dam_break", "surge front error (MAE in Z, T <= 3)"),
                                (axes[1], "water_jet", "jet range error (fraction of 3.97 m)")):
            pts = [r for r in acc if r["case"] == case]
            if not pts:
                continue
            for b, marker in (("cpu", "o"), ("host", "s")):
                sel = [r for r in pts if r["backend"] == b]
                ax.scatter([r["wall_per_simulated_second"] for r in sel], [r["error"] for r in sel], marker=marker, label=b)
                for r in sel:
                    ax.annotate(f"{r['particles'] // 1000}k", (r["wall_per_simulated_second"], r["error"]), fontsize=7)
            front = pareto([(r["wall_per_simulated_second"], r["error"]) for r in pts])
            ax.plot([pts[i]["wall_per_simulated_second"] for i in front], [pts[i]["error"] for i in front], "k--", lw=1,
                    label="Pareto front")
            ax.set_xscale("log")
            ax.set_xlabel("wall seconds per simulated second")
            ax.set_ylabel(label)
            ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out, "accuracy_cost.png"), dpi=120)
    if bench and os.path.exists(bench):
        with open(bench) as f:
            rows = [r for r in csv.DictReader(f) if r["workload"].startswith("dam_break")]
        fig, ax = plt.subplots(figsize=(5, 3.8))
        for b in sorted({r["backend"] for r in rows}):
            sel = sorted((int(r["particles"]), float(r["ms_per_step"])) for r in rows if r["backend"] == b)
            ax.loglog([s[0] for s in sel], [s[1] for s in sel], "o-", label=b)
        ax.set_xlabel("particles")
        ax.set_ylabel("ms per step")
        ax.set_title("Scaling: dam break")
        ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(out, "scaling.png"), dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "studies"))
    ap.add_argument("--bench", default="", help="sph_bench's bench.csv for the scaling chart")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only", choices=["stability", "clustering", "accuracy"], help="run one study only")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    stab, acc = [], []
    if args.only in (None, "stability"):
        print("[studies] stability map", flush=True)
        stab = stability_map(args, args.out)
    if args.only in (None, "clustering"):
        print("[studies] tensile clustering", flush=True)
        clustering(args, args.out)
    if args.only in (None, "accuracy"):
        print("[studies] accuracy against cost", flush=True)
        acc = accuracy_cost(args, args.out)
    charts(args.out, stab, acc, args.bench)
    print(f"[studies] written: {args.out}/stability_map.csv, clustering.csv, accuracy_cost.csv and the PNG charts")


if __name__ == "__main__":
    main()
