"""Issue 15: calibrate the two thickness mechanisms on Table 4 and compare them (not a test).

Run: python docs/analysis/compare_thickness_mechanisms.py [OUTDIR] [MODEL ...] [--no-loo]
Writes OUTDIR/calibration_<model>.toml for models v4 (drive viscous friction through the leaves),
v4-coulomb (its Coulomb friction), v3 (a constant drive heat) and v3-overconstraint,
and prints R², leave-one-out R² and the parameters with standard errors; then what else each
predicts at the Fig. 9 settings (RMS against RFCMS, v = 0.5 m/s, a = 10 m/s², 0.3 mm).
A few minutes each on two cores.
"""

import sys
import time
from pathlib import Path

import pandas as pd

from rsm_lrg.datasets import data_path, load_table4
from rsm_lrg.surrogate import simulate
from rsm_lrg.surrogate.calibrate import calibrate, calibration_toml, file_sha256


def linearised_loo_r2(cal, data, params=None):
    """Leave-one-out R² from the linearised model at the optimum (PRESS with the leverages of
    the Jacobian, e_i/(1 - h_ii); Cook & Weisberg, Residuals and Influence in Regression, 1982,
    Section 2.2): a cheap stand-in for the refits, checked against them on the shipped model."""
    import numpy as np

    obs = np.asarray(cal.observed)
    base = np.asarray(cal.predicted)
    cols = []
    for p in cal.parameters:
        h = 1e-3 * (p.upper - p.lower)
        step = h if p.value + h <= p.upper else -h
        vals = cal.parameter_values()
        vals[p.name] = p.value + step
        cols.append((simulate(data, noise_sd=0, calibration=vals).tcr_c_per_min.to_numpy() - base) / step)
    J = np.column_stack(cols)
    H = J @ np.linalg.solve(J.T @ J, J.T)
    e = (obs - base) / (1 - np.diag(H))
    return 1 - np.sum(e ** 2) / np.sum((obs - obs.mean()) ** 2)


def main(out="."):
    out = Path(out)
    t4 = load_table4()
    sha = file_sha256(data_path("table4.csv"))
    for model in [a for a in sys.argv[2:] if not a.startswith("--")] or ("v4", "v4-coulomb", "v3", "v3-overconstraint"):
        t = time.time()
        loo = "--no-loo" not in sys.argv
        cal = calibrate(t4, "tcr_c_per_min", model=model, source="table4.csv", data_sha256=sha, loo=loo,
                        grid_points=None if loo else 5)
        cmd = f"rsm-lrg calibrate data/table4.csv --response tcr_c_per_min --model {model} -o data/calibration.toml --force"
        (out / f"calibration_{model}.toml").write_text(calibration_toml(cal, cmd))
        print(f"== {model} ({time.time() - t:.0f} s)")
        print(cal.summary())
        print(f"  linearised leave-one-out R2 {linearised_loo_r2(cal, t4):.4f}")
        rows = [dict(thickness_m=3e-4, stroke_m=s, velocity_m_s=0.5, acceleration_m_s2=10.0, stage=st)
                for s in (0.075, 0.06, 0.04) for st in ("rfcms", "rms")]
        fig9 = simulate(pd.DataFrame(rows), noise_sd=0, calibration=cal)
        print(fig9[["stroke_m", "stage", "tcr_c_per_min", "heat_w", "wear_volume_m3_per_h"]].to_string())
        sys.stdout.flush()


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
