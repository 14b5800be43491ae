"""Issue 15: leave-one-out R^2 of the drive-heat models with c_v refitted on a grid (not a test).

Run: python docs/analysis/profile_loo.py   (a few minutes on two cores)

Given the block's viscous friction c_v (it enters the stage dynamics), the heat share and the
drive-heat coefficient enter kappa linearly; so each fold (one run left out) is refitted by a
profile: for every c_v on a 1 N s/m grid over its bounds [0, 30], linear least squares for the
other two; the best c_v of the fold predicts the run left out. Coarser than the local refits of
`rsm-lrg calibrate` (the stick-slip dynamics make kappa a rough function of c_v, and the grid
lets a fold jump to another c_v), so a little harsher. Result (2026-11-23):

    v4          c_v 4   R2 0.879   LOO 0.847
    v4-coulomb  c_v 8   R2 0.868   LOO 0.825
    v3          c_v 27  R2 0.857   LOO 0.821
"""

import numpy as np

from rsm_lrg.datasets import load_table4
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.surrogate.design_input import read_design_arrays
from rsm_lrg.surrogate.runs import evaluate_rows

LAWS = {"v4": {"drive_viscous_n_s_m": 1.0}, "v4-coulomb": {"drive_friction_n": 1.0}, "v3": {"drive_heat_w": 1.0}}
CV = np.arange(0.0, 30.01, 1.0)


def main():
    d = load_table4()
    obs = d.tcr_c_per_min.to_numpy()
    sst = float(np.sum((obs - obs.mean()) ** 2))
    base = LRGParams()
    arr = read_design_arrays(d.drop(columns=["tcr_c_per_min"]), base)
    F, G = {}, {k: {} for k in LAWS}
    for cv in CV:
        p = base.with_overrides(viscous_friction_n_s_m=cv)
        F[cv] = evaluate_rows(arr, params=p, calibration={"heat_partition": 1.0}, memo=True)["tcr_c_per_min"]
        for k, c in LAWS.items():
            G[k][cv] = evaluate_rows(arr, params=p, calibration={"heat_partition": 1e-12, **c},
                                     memo=True)["tcr_c_per_min"] - 1e-12 * F[cv]
    n = obs.size
    for k in LAWS:
        def best(idx, k=k):
            out = None
            for cv in CV:
                X = np.column_stack([F[cv], G[k][cv]])
                b = np.linalg.lstsq(X[idx], obs[idx], rcond=None)[0]
                sse = float(np.sum((obs[idx] - X[idx] @ b) ** 2))
                if out is None or sse < out[0]:
                    out = (sse, cv, b, X)
            return out

        sse, cv, b, _ = best(np.arange(n))
        lp = np.empty(n)
        for i in range(n):
            _, _, bi, Xi = best(np.delete(np.arange(n), i))
            lp[i] = Xi[i] @ bi
        print(f"{k:11s} c_v {cv:g}  share {b[0]:.4f}  coefficient {b[1]:.4g}  R2 {1 - sse / sst:.4f}  "
              f"LOO {1 - np.sum((obs - lp) ** 2) / sst:.4f}", flush=True)


if __name__ == "__main__":
    main()
