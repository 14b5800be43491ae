"""Issue 15: is there a velocity-convex heat source the Table 4 data ask for? (not a test)

Run: python docs/analysis/velocity_convexity.py CALIBRATION.toml
Takes a calibration (default: the shipped one), its virtual runs on Table 4, and adds one more
heat source per cycle, beta * <|v|^p> (cycle mean over the trapezoidal profile of the carriage,
rsm_lrg.physics.motion), through the same thermal unit response (K per W at 50 min): fits obs ~ alpha * pred + beta * g
(beta >= 0, NNLS; alpha stands for refitting the heat share) for p = 1 ... 6 and prints the R² gained, the heat at
the centre run; and the residual's projection on (1, C, C²) in coded velocity.
Candidate mechanisms and their exponents: lubricant churning/viscous shear p = 2 (already in
c_v), seal lip friction p ~ 0.3-0.5 (Hamrock, Fundamentals of Fluid Film Lubrication, ch. on
seals: hydrodynamic seal friction ~ (eta v)^0.5), ball skidding/spin with a speed-dependent
coefficient p ~ 2-3, windage/air drag of the stage p = 3 (drag force ~ v^2).
"""

import sys

import numpy as np

from rsm_lrg.datasets import data_path, load_table4
from rsm_lrg.physics import motion
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.surrogate import simulate
from rsm_lrg.surrogate.calibrate import load_calibration
from rsm_lrg.surrogate.runs import thermal_unit_response


def cycle_mean_abs_power(s, v, a, p, n=4000):
    """Cycle mean of |v|^p for each row (arrays s, v, a) [(m/s)^p]."""
    out = []
    for si, vi, ai in np.broadcast(s, v, a):
        T = float(motion.cycle_time(si, vi, ai))
        t = np.linspace(0.0, T, n + 1)
        _, vel, _ = motion.reciprocating_profile(t, si, vi, ai)
        out.append(np.trapezoid(np.abs(vel) ** p, t) / T)
    return np.array(out)


def main(path=None):
    cal = load_calibration(path or data_path("calibration.toml"))
    d = load_table4()
    obs = d.tcr_c_per_min.to_numpy()
    pred = simulate(d, noise_sd=0, calibration=cal).tcr_c_per_min.to_numpy()
    hist, _ = thermal_unit_response(LRGParams().to_dict(), 50.0)
    unit = (hist[50] - hist[0]) / 50.0  # K/min per W over the 50-min test
    sst = np.sum((obs - obs.mean()) ** 2)
    r2 = 1 - np.sum((obs - pred) ** 2) / sst
    print(f"model {cal.model or '?'}: R2 {r2:.4f}")
    s, v, a = (d[c].to_numpy() for c in ("stroke_m", "velocity_m_s", "acceleration_m_s2"))
    X = np.column_stack([np.ones_like(obs), (v - 0.5) / 0.1, ((v - 0.5) / 0.1) ** 2])
    print("residual on (1, C, C^2):", np.round(np.linalg.lstsq(X, obs - pred, rcond=None)[0], 5))
    for p in (0.5, 1, 2, 3, 4, 6):
        g = unit * cycle_mean_abs_power(s, v, a, p)
        # the calibrated heat rescaled by alpha (about what refitting the heat share does) plus
        # the new source: obs ~ alpha * pred + beta * g, beta >= 0
        from scipy.optimize import nnls

        (alpha, beta), _ = nnls(np.column_stack([pred, g]), obs)
        new = alpha * pred + beta * g
        r2n = 1 - np.sum((obs - new) ** 2) / sst
        centre = beta * float(cycle_mean_abs_power(0.05, 0.5, 30.0, p)[0])
        print(f"p = {p:3}: beta {beta:.4g} W/(m/s)^p, heat at the centre run {centre * 1e3:.1f} mW, alpha {alpha:.3f}, "
              f"R2 {r2n:.4f} (+{r2n - r2:.4f})")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
