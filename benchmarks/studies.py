#!/usr/bin/python3
"""Studies behind the charts: where each method becomes unstable, how much tensile clustering near
pressure prevents, and accuracy against cost. Runs build/sph_run and writes CSV files and PNG charts.

  stability map    largest stable fixed time step on the dam break, per integrator, for the two ways of
                   handling tensile instability (clamped pressure; negative pressure kept + near
                   pressure), with Tait and ideal equations of state (bisection on dt); stable = no
                   blow-up, no runaway speed, mean density within 10% of rest density
  clustering       zero-g drop with and without near pressure: smallest pair distance, clustered share
  accuracy-cost    dam-break surge-front error and water-jet range error against wall time per simulated
                   second, one point per method (integrator, equation of state, tensile handling, walls), back end,
                   resolution and time step; unstable runs listed; Pareto front marked
  solvers          per pressure solver (WCSPH, DFSPH, PBF; issue 12): the largest stable fixed time step on the
                   dam break, and the dam-break surge-front error against wall time per simulated second
                   at several resolutions, each solver at its own step (solvers.csv, solvers.png)
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

from experiments import G, A, AXIM_RANGE, dam_break_errors, jet_range
from ply_frames import read_ply

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INTEGRATORS = ["explicit_euler", "semi_implicit_euler", "velocity_verlet", "modified_velocity_verlet", "leapfrog"]
VARIANTS = {"clamp": ["sph.negative_pressure=clamp", "fluids.0.near_stiffness=0"],
            "keep+near": ["sph.negative_pressure=keep", "fluids.0.near_stiffness=4"]}
# Method variants in the accuracy study, against each scene's own settings ("scene").
ACCURACY_VARIANTS = {"dam_break": {"scene": [], "ideal": ["sph.equation_of_state=ideal"], "keep+near": VARIANTS["keep+near"],
                                   "mirror": ["sph.walls=mirror"]},
                     "water_jet": {"scene": []}}


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

                # 6 bisections in log space between 0.01 and 4 ms: the answer is within about 10%. The
                # lower end (10,000 steps, the costliest run) is tried only if no larger step was stable.
                lo, hi = 1e-5, 4e-3
                if stable(hi):
                    best = hi
                else:
                    for _ in range(iterations):
                        mid = math.sqrt(lo * hi)
                        lo, hi = (mid, hi) if stable(mid) else (lo, mid)
                    best = lo if lo > 1e-5 or stable(lo) else 0.0
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


def column(rows, key):
    return np.array([float(r[key]) for r in rows])


def surge_error(rows):
    return dam_break_errors(column(rows, "time"), column(rows, "front_x"), column(rows, "height_at_x0"))["surge_front_mae_T_le_3"]


def jet_range_error(rows):
    return abs(jet_range(column(rows, "time"), column(rows, "front_x")) - AXIM_RANGE) / AXIM_RANGE


# One accuracy-against-cost point: run the case, measure its error, or mark it unstable (exit status 3).
CASES = {"dam_break": ("dam_break.json", 0.17, 0.002, surge_error),  # 0.17 s is T = 3.15
         "water_jet": ("water_jet.json", 1.2, 0.01, jet_range_error)}


def accuracy_point(args, out, case, backend, resolution, integrator, variant, dt):
    scene, t_end, metrics_every, error = CASES[case]
    sets = [f"resolution.particles_across={resolution}", f"integrator={integrator}"] + ACCURACY_VARIANTS[case][variant]
    if dt != "scene":
        sets += ["time_step.mode=adaptive"] if dt == "adaptive" else ["time_step.mode=fixed", f"time_step.dt={dt}"]
    rc, s, m, wall = sph_run(args.build, scene, t_end, os.path.join(out, "acc_run"), sets, backend=backend,
                             metrics_every=metrics_every)
    stable = rc == 0 and bool(m)
    row = {"case": case, "integrator": integrator, "variant": variant, "backend": backend, "resolution": resolution,
           "particles": int(s.get("particles", 0)), "dt": dt, "steps": int(s.get("steps", 0)), "stable": stable,
           "wall_per_simulated_second": wall / float(s["simulated_time"]) if stable else float("nan"),
           "error": error(m) if stable else float("nan")}
    dt_text = dt if dt in ("adaptive", "scene") else f"{float(dt) * 1e3:g} ms"
    result = (f"error {row['error']:.3f}, {row['wall_per_simulated_second']:.1f} s per simulated s" if stable
              else "unstable")
    print(f"  accuracy-cost: {case} {resolution:2d} across, {integrator} ({variant}), dt {dt_text}, {backend}: "
          f"{row['particles']} particles, {result}", flush=True)
    return row


def accuracy_cost(args, out):
    """Points along four axes: resolution, back end, method (integrator; equation of state; clamped pressure
    or kept pressure with near pressure; penalty or mirror walls) and time step (the scene's adaptive step
    or a fixed one)."""
    mvv = "modified_velocity_verlet"
    points = []  # (case, backend, resolution, integrator, variant, dt)
    if args.quick:
        points += [("dam_break", b, 10, mvv, "scene", "scene") for b in ("cpu", "host")]
        points += [("dam_break", "host", 10, i, "scene", "3e-4") for i in ("semi_implicit_euler", mvv)]
        points += [("water_jet", "host", 6, mvv, "scene", "scene")]
    else:
        # resolution and back end: cpu only where it fits the time budget (it gives the same answers)
        points += [("dam_break", "host", n, mvv, "scene", "scene") for n in (12, 16, 20, 26)]
        points += [("dam_break", "cpu", n, mvv, "scene", "scene") for n in (12, 16)]
        points += [("dam_break", "host", n, mvv, "scene", "2e-4") for n in (20, 26)]  # fixed step, finer particles
        # method and time step at 16 across
        for integ in INTEGRATORS:
            for dt in ("2e-4", "3.5e-4") if integ != "explicit_euler" else ("5e-5",):
                points.append(("dam_break", "host", 16, integ, "scene", dt))
        points += [("dam_break", "host", 16, i, "scene", "scene") for i in INTEGRATORS if i not in (mvv, "explicit_euler")]
        points += [("dam_break", "host", 16, mvv, v, dt) for v in ("ideal", "keep+near", "mirror") for dt in ("scene", "2e-4")]
        # water jet: resolution with the thesis's method (dt 1 ms), then integrators and time steps at 7 across
        points += [("water_jet", "host", n, mvv, "scene", "scene") for n in (7, 10, 13)]
        points += [("water_jet", "host", 7, i, "scene", "scene") for i in INTEGRATORS if i != mvv]
        points += [("water_jet", "host", 7, mvv, "scene", dt) for dt in ("5e-4", "2e-3")]
    rows = [accuracy_point(args, out, *p) for p in points]
    write_csv(os.path.join(out, "accuracy_cost.csv"), rows)
    return rows


# Each solver as a user would run it: its scene keys and its own time step ("adaptive": the scene's adaptive
# step, the CFL step for DFSPH; a number: that fixed step).
# dfsph06: DFSPH at the CFL factor 0.6 instead of [BK15]'s 0.4 (its fixed-step stability is dfsph's, so it is
# left out of the bisection).
# wcsph_cubic: WCSPH with the cubic spline for density and gradients (sph.kernel) instead of Poly6 and Spiky.
SOLVERS = {"wcsph": ([], "adaptive"), "wcsph_cubic": (["sph.kernel=cubic_spline"], "adaptive"),
           "dfsph": (["solver=dfsph"], "adaptive"),
           "dfsph06": (["solver=dfsph", "time_step.cfl_velocity=0.6", "time_step.max=3e-3"], "adaptive"),
           "pbf": (["solver=pbf"], "4e-3"), "pbf8": (["solver=pbf", "pbf.iterations=8"], "4e-3")}


def solver_stable(args, out, solver, dt, t_run, resolution):
    """A fixed-step dam break that ends without a blow-up, below a runaway speed and within 10% of rest
    density (the stability map's rule)."""
    sets = [f"resolution.particles_across={resolution}", "time_step.mode=fixed", f"time_step.dt={dt}"] + SOLVERS[solver][0]
    rc, _, m, _ = sph_run(args.build, "dam_break.json", t_run, os.path.join(out, "solver_run"), sets)
    return (rc == 0 and bool(m) and float(m[-1]["v_max"]) < 5.0 * math.sqrt(2 * G * 2 * A) and
            float(m[-1]["density_error_mean"]) < 0.10)


def solvers(args, out):
    """Largest stable fixed step per solver (bisection in log space between 0.01 and 8 ms, as the stability
    map), then surge-front error against cost at each solver's own step."""
    rows = []
    t_run = 0.05 if args.quick else 0.1
    for solver in SOLVERS:
        if solver == "dfsph06":
            continue
        lo, hi = 1e-5, 8e-3
        if solver_stable(args, out, solver, hi, t_run, 12):
            best = hi
        else:
            for _ in range(2 if args.quick else 6):
                mid = math.sqrt(lo * hi)
                lo, hi = (mid, hi) if solver_stable(args, out, solver, mid, t_run, 12) else (lo, mid)
            best = lo if lo > 1e-5 or solver_stable(args, out, solver, lo, t_run, 12) else 0.0
        print(f"  solvers: {solver} largest stable fixed dt {best:.2e} s", flush=True)
        rows.append({"study": "stability", "solver": solver, "resolution": 12, "dt": best, "steps": 0, "particles": 0,
                     "stable": True, "wall_per_simulated_second": float("nan"), "error": float("nan"),
                     "iterations_per_step": float("nan")})
    resolutions = (10,) if args.quick else (12, 16, 20)
    scene, t_end, metrics_every, error = CASES["dam_break"]
    for solver, (sets0, dt) in SOLVERS.items():
        for n in resolutions:
            sets = [f"resolution.particles_across={n}"] + sets0
            sets += ["time_step.mode=adaptive"] if dt == "adaptive" else ["time_step.mode=fixed", f"time_step.dt={dt}"]
            rc, s, m, wall = sph_run(args.build, scene, t_end, os.path.join(out, "solver_run"), sets, metrics_every=metrics_every)
            stable = rc == 0 and bool(m)
            iters = s.get("density_solver_iterations", s.get("constraint_iterations", ""))
            it = float(re.match(r"mean ([0-9.eE+-]+)", iters).group(1)) if iters else 0.0
            row = {"study": "accuracy", "solver": solver, "resolution": n, "dt": dt, "steps": int(s.get("steps", 0)),
                   "particles": int(s.get("particles", 0)), "stable": stable,
                   "wall_per_simulated_second": wall / float(s["simulated_time"]) if stable else float("nan"),
                   "error": error(m) if stable else float("nan"), "iterations_per_step": it}
            result = (f"error {row['error']:.3f}, {row['wall_per_simulated_second']:.1f} s per simulated s, "
                      f"{row['steps']} steps" if stable else "unstable")
            print(f"  solvers: {solver} {n} across, dt {dt}: {row['particles']} particles, {result}", flush=True)
            rows.append(row)
    write_csv(os.path.join(out, "solvers.csv"), rows)
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


def solver_chart(plt, out, rows):
    def label(solver):
        names = {"pbf8": "PBF, 8 it.", "pbf": "PBF, 4 it.", "dfsph06": "DFSPH, CFL 0.6", "wcsph_cubic": "WCSPH, cubic"}
        return names.get(solver, solver.upper())

    colours = {"wcsph": "tab:blue", "wcsph_cubic": "tab:cyan", "dfsph": "tab:red", "dfsph06": "tab:purple", "pbf": "tab:green", "pbf8": "tab:olive"}
    fig, axes = plt.subplots(1, 2, figsize=(11, 4))
    stab = [r for r in rows if r["study"] == "stability"]
    axes[0].bar([label(r["solver"]) for r in stab], [r["dt"] * 1e3 for r in stab],
                color=[colours[r["solver"]] for r in stab])
    axes[0].set_ylabel("largest stable fixed dt [ms]")
    axes[0].set_title("Dam break (12 across), fixed step")
    for solver, c in colours.items():
        pts = [r for r in rows if r["study"] == "accuracy" and r["solver"] == solver and r["stable"]]
        axes[1].plot([r["wall_per_simulated_second"] for r in pts], [r["error"] for r in pts], "o-", color=c,
                     label=f"{label(solver)} (dt {pts[0]['dt'] if pts else '-'})")
        for r in pts:
            axes[1].annotate(f"{r['particles'] / 1000:.1f}k", (r["wall_per_simulated_second"], r["error"]), fontsize=7,
                             xytext=(4, 3), textcoords="offset points")
        for r in rows:
            if r["study"] == "accuracy" and r["solver"] == solver and not r["stable"]:
                axes[1].text(0.01, 0.95 - 0.05 * list(colours).index(solver),
                             f"{label(solver)} unstable at {r['particles'] / 1000:.1f}k particles ({r['resolution']} across)",
                             transform=axes[1].transAxes,
                             fontsize=7, color=c)
    axes[1].set_xscale("log")
    axes[1].set_xlabel("wall seconds per simulated second (log)")
    axes[1].set_ylabel("surge front error (MAE in Z, T <= 3)")
    axes[1].set_title("Dam break vs Martin & Moyce, per solver")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "solvers.png"), dpi=120)


def charts(out, stab, acc, bench, solver_rows=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    if solver_rows:
        solver_chart(plt, out, solver_rows)
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
        colours = dict(zip(INTEGRATORS, ["tab:gray", "tab:green", "tab:orange", "tab:blue", "tab:purple"]))

        def marker(r):
            if r["variant"] != "scene":
                return {"ideal": "P", "keep+near": "X", "mirror": "D"}[r["variant"]]
            if r["dt"] == "scene":
                return "o"
            dt = float(r["dt"])
            if r["case"] == "water_jet":
                return "s" if dt < 1e-3 else "^"
            return "v" if dt <= 1e-4 else ("s" if dt <= 2.5e-4 else "^")

        fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
        for ax, case, label in ((axes[0], "dam_break", "surge front error (MAE in Z, T <= 3)"),
                                (axes[1], "water_jet", "jet range error (fraction of 3.97 m)")):
            pts = [r for r in acc if r["case"] == case and r["stable"]]
            if not pts:
                continue
            for r in pts:
                c = colours[r["integrator"]]
                ax.scatter(r["wall_per_simulated_second"], r["error"], marker=marker(r), s=40,
                           facecolors="none" if r["backend"] == "cpu" else c, edgecolors=c)
                if r["integrator"] == "modified_velocity_verlet" and r["variant"] == "scene" and r["dt"] == "scene":
                    ax.annotate(f"{r['particles'] / 1000:.1f}k", (r["wall_per_simulated_second"], r["error"]),
                                fontsize=7, xytext=(4, 3), textcoords="offset points")
            front = pareto([(r["wall_per_simulated_second"], r["error"]) for r in pts])
            ax.plot([pts[i]["wall_per_simulated_second"] for i in front], [pts[i]["error"] for i in front], "k--", lw=1)
            unstable = [r for r in acc if r["case"] == case and not r["stable"]]
            if unstable:
                ax.text(0.01, 0.01, "unstable: " + "; ".join(
                    f"{r['integrator'].replace('_', ' ')} {r['variant'] if r['variant'] != 'scene' else ''} dt {r['dt']}"
                    for r in unstable), transform=ax.transAxes, fontsize=6, va="bottom", wrap=True)
            ax.set_xscale("log")
            ax.set_xlabel("wall seconds per simulated second (log)")
            ax.set_ylabel(label)
            ax.set_title({"dam_break": "Dam break vs Martin & Moyce", "water_jet": "Water jet vs AXIM range"}[case])
        from matplotlib.lines import Line2D
        handles = [Line2D([], [], ls="", marker="o", color=colours[i], label=i.replace("_", " ")) for i in INTEGRATORS]
        handles += [Line2D([], [], ls="", marker=m, color="k", markerfacecolor=f, label=l) for m, f, l in (
            ("o", "k", "scene's time step, host"), ("o", "none", "the same on cpu"),
            ("v", "k", "fixed dt 0.05 ms (dam)"), ("s", "k", "fixed dt 0.2 ms (dam), 0.5 ms (jet)"),
            ("^", "k", "fixed dt 0.35 ms (dam), 2 ms (jet)"), ("P", "k", "ideal gas EOS, else Tait"),
            ("X", "k", "kept pressure + near pressure,\nelse clamped"), ("D", "k", "mirror walls, else penalty"))]
        handles.append(Line2D([], [], ls="--", color="k", lw=1, label="Pareto front"))
        fig.legend(handles=handles, loc="center right", fontsize=7)
        fig.tight_layout(rect=(0, 0, 0.8, 1))
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
    ap.add_argument("--only", choices=["stability", "clustering", "accuracy", "solvers"], help="run one study only")
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
    solver_rows = []
    if args.only in (None, "solvers"):
        print("[studies] solvers", flush=True)
        solver_rows = solvers(args, args.out)
    charts(args.out, stab, acc, args.bench, solver_rows)
    print(f"[studies] written: {args.out}/stability_map.csv, clustering.csv, accuracy_cost.csv, solvers.csv and the PNG charts")


if __name__ == "__main__":
    main()
