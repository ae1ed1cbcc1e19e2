"""The piston wave maker (scenes/wave_maker.json) against linear wave-maker theory: Biesel's transfer
function for a piston, H / S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh) (Biesel & Suquet 1951; Dean & Dalrymple,
Water Wave Mechanics for Engineers and Scientists, 1991, section 6.3), with k from the dispersion relation
omega^2 = g k tanh kh. Called by validate.py, which runs the scene; this module measures the wave height at
the scene's gauges between the passing of the first front and the return of the reflection from the far
wall, and plots the gauges."""
import math
import os

import numpy as np

G = 9.81


def wavenumber(period, depth):
    """k [1/m] solving omega^2 = g k tanh(k depth) (Newton's method from the deep-water value)."""
    omega = 2.0 * math.pi / period
    k = omega ** 2 / G
    for _ in range(50):
        f = G * k * math.tanh(k * depth) - omega ** 2
        df = G * math.tanh(k * depth) + G * k * depth / math.cosh(k * depth) ** 2
        k -= f / df
    return k


def biesel_piston(kh):
    """Wave height over stroke, H / S, of a piston wave maker in water of depth h."""
    return 2.0 * (math.cosh(2 * kh) - 1.0) / (math.sinh(2 * kh) + 2 * kh)


def group_velocity(k, depth, period):
    c = 2.0 * math.pi / period / k
    return 0.5 * c * (1.0 + 2 * k * depth / math.sinh(2 * k * depth))


def compare(m, out, plt=None, save_chart=None, depth=0.15, stroke=0.04, period=0.8, paddle_x=0.05, tank=1.2,
            viscosity=None):
    """m: metrics.csv columns depth_xNNN (a gauge NNN cm from the tank's end); tank: its length [m]. The
    window at each gauge: from a period after the front (at the group velocity) until the first reflection
    from the far wall can return (at the phase speed, the fastest linear waves). viscosity: {"alpha", "h",
    "c0"} of the run, for the decay the artificial viscosity predicts."""
    k = wavenumber(period, depth)
    ratio = biesel_piston(k * depth)
    cg = group_velocity(k, depth, period)
    result = {"wavelength_m": 2 * math.pi / k, "kh": k * depth, "biesel_H_over_S": ratio, "biesel_H_m": ratio * stroke,
              "group_velocity_m_s": cg, "gauges": {}}
    t = m["time"]
    for name in sorted(c for c in m if c.startswith("depth_x")):
        x = int(name[len("depth_x"):]) / 100.0
        start = (x - paddle_x) / cg + period  # a period after the front, past its transient
        end = (2 * tank - x - paddle_x) / (2.0 * math.pi / period / k)  # a reflection could be back
        sel = (t >= start) & (t <= end)
        r = {"x_m": x, "window_s": [start, end]}
        if end - start >= period and sel.sum() > 10:
            # The least-squares sinusoid at the paddle's period: particle noise averages out, where the
            # largest crest minus the deepest trough would add it.
            w = 2.0 * math.pi / period
            ts, d = t[sel], m[name][sel]
            a = np.column_stack([np.cos(w * ts), np.sin(w * ts), np.ones_like(ts)])
            coef, *_ = np.linalg.lstsq(a, d, rcond=None)
            r["height_m"] = float(2.0 * math.hypot(coef[0], coef[1]))
            r["height_over_biesel"] = r["height_m"] / result["biesel_H_m"]
            r["crest_to_trough_m"] = float(d.max() - d.min())
            r["mean_depth_m"] = float(coef[2])
            r["residual_rms_m"] = float(np.sqrt(np.mean((a @ coef - d) ** 2)))
        result["gauges"][name[len("depth_"):]] = r
    # Damping along the tank: the measured decay between the first two gauges, the height it implies at the
    # paddle, and the decay the artificial viscosity alone predicts (its kinematic viscosity in 3-D,
    # nu = alpha h c0 / 10 [Monaghan 2005], damps a linear wave's amplitude at 2 nu k^2 per second, so per
    # metre of travel at the group velocity 2 nu k^2 / c_g).
    fitted = [g for g in result["gauges"].values() if "height_m" in g]
    if len(fitted) >= 2:
        a, b = fitted[0], fitted[1]
        rate = math.log(a["height_m"] / b["height_m"]) / (b["x_m"] - a["x_m"])
        result["decay_per_m"] = rate
        result["height_at_paddle_m"] = a["height_m"] * math.exp(rate * (a["x_m"] - paddle_x))
        result["height_at_paddle_over_biesel"] = result["height_at_paddle_m"] / result["biesel_H_m"]
    if viscosity is not None:
        nu = viscosity["alpha"] * viscosity["h"] * viscosity["c0"] / 10.0
        result["artificial_nu_m2_s"] = nu
        result["predicted_decay_per_m"] = 2.0 * nu * k * k / cg
    if plt:
        fig, ax = plt.subplots(figsize=(8, 3.6))
        for name in sorted(c for c in m if c.startswith("depth_x")):
            g = result["gauges"][name[len("depth_"):]]
            line, = ax.plot(t, m[name], lw=1, label=f"gauge at x = {g['x_m']} m")
            if "height_m" in g:
                ax.axvspan(g["window_s"][0], g["window_s"][1], color=line.get_color(), alpha=0.12)
        ax.axhline(depth + 0.5 * result["biesel_H_m"], color="k", ls=":", lw=1, label=f"still water +- Biesel's H / 2 ({100 * result['biesel_H_m']:.1f} cm)")
        ax.axhline(depth - 0.5 * result["biesel_H_m"], color="k", ls=":", lw=1)
        ax.set_xlabel("t [s]")
        ax.set_ylabel("water depth [m]")
        ax.legend(fontsize=8, loc="lower left")
        save_chart(fig, os.path.join(out, "wave_maker_gauges.png"))
    return result
