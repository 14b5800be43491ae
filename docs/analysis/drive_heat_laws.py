"""Issue 15: which law of the drive-side heat do the Table 4 data favour? (not a test)

Run: python docs/analysis/drive_heat_laws.py   (about a minute on two cores)

The drive heat reaches the carriage through the leaves (G = n lambda w y / l, share G/(G + G_s),
behind the working stage's heat capacity); what differs is how the heat P_d put into the stage
depends on the motion. Candidates, each one parameter with a physical meaning:

* constant P_d [W] (model v3: a motor or coupling that warms the stage whatever the motion);
* P_d = F_d <|v|> (model v4: Coulomb friction of the drive element fixed to the stage --
  a nut, coupling or cable carrier -- the same law as the guide's own Eq. 8 heat);
* P_d ~ <v^2> (viscous drag in the drive), ~ <|v|^3> (air drag of the stage),
  ~ <a^2> duty (copper losses of a motor pushing the stage's mass, I^2 R ~ (m a)^2).

For each law and a few values of the block's viscous friction c_v, the heat share and the law's
coefficient enter kappa linearly, so they are fitted by linear least squares; leave-one-out R^2
from the hat matrix (c_v held: slightly optimistic against the refits of `rsm-lrg calibrate`,
which refit c_v too). Result (2026-11-23; c_v on the grid CV below, the best LOO of each law;
physics of issue 15: elastic hinge with held ends, zeta 0.02, drive heat behind the stage's
heat capacity):

    law        c_v  R2      LOO (c_v held)   LOO (c_v refitted on the grid, /tmp script)
    constant   30   0.857   0.831            0.821  (v3)
    <|v|>       8   0.868   0.841            0.825  (v4-coulomb)
    <v^2>       4   0.879   0.854            0.847  (v4)
    <a^2>       4   0.869   0.841
    <|v|^3>     2   0.884   0.863

Six laws were tried on 27 runs (with the over-constraint load of v3-overconstraint): a winner
picked this way is flattered by the choice itself, and the 0.01-0.02 between the laws is of the
size such a choice can win by chance. The shipped model v4 takes <v^2> because it is the law of
a physical mechanism of the right size -- viscous friction of the drive element (a lubricated
nut or seal, or the eddy-current drag of a linear motor), the same law as the block's own c_v
(LuGre sigma_2) -- and about 1.5 N s/m of it is plausible. <|v|^3> fits better but has no
mechanism of that size: air drag on the stage (1/2 rho C_d A v^3 with A ~ 2e-3 m^2) is about
1e-4 W, four orders short, and its heat goes to the air, not into the stage. <a^2> (copper
losses of a motor pushing the stage, I^2 R ~ (m a)^2) does no better than <|v|>. All laws that
grow with v say the same thing about the data: kappa is convex in velocity (Eq. 19's C^2 =
+0.0027), which neither Coulomb friction (concave in v at fixed stroke: the mean speed is
v/(1 + v^2/(a s))) nor a constant heat gives.
"""

import numpy as np

from rsm_lrg.datasets import load_table4
from rsm_lrg.physics import motion
from rsm_lrg.physics.params import LRGParams
from rsm_lrg.surrogate.design_input import read_design_arrays
from rsm_lrg.surrogate.runs import evaluate_rows

CV = (0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 15.0, 20.0, 30.0)


def main():
    d = load_table4()
    obs = d.tcr_c_per_min.to_numpy()
    sst = float(np.sum((obs - obs.mean()) ** 2))
    base = LRGParams()
    arr = read_design_arrays(d.drop(columns=["tcr_c_per_min"]), base)
    s, v, a = (d[c].to_numpy() for c in ("stroke_m", "velocity_m_s", "acceleration_m_s2"))
    T = motion.cycle_time(s, v, a)
    mean_speed = 2 * s / T
    ta = 4 * np.minimum(v / a, np.sqrt(s / a)) / T           # share of the cycle spent accelerating
    laws = {"constant": np.ones_like(s), "<|v|>": mean_speed, "<v^2>": motion.mean_square_speed(s, v, a),
            "<a^2>": a ** 2 * ta, "<|v|^3>": motion.mean_square_speed(s, v, a) ** 1.5}
    for cv in CV:
        p = base.with_overrides(viscous_friction_n_s_m=cv)
        f = evaluate_rows(arr, params=p, calibration={"heat_partition": 1.0}, memo=True)["tcr_c_per_min"]
        g = evaluate_rows(arr, params=p, calibration={"heat_partition": 1e-12, "drive_heat_w": 1.0},
                          memo=True)["tcr_c_per_min"] - 1e-12 * f
        for name, law in laws.items():
            X = np.column_stack([f, g * law])
            b = np.linalg.lstsq(X, obs, rcond=None)[0]
            e = obs - X @ b
            h = np.einsum("ij,ji->i", X, np.linalg.solve(X.T @ X, X.T))
            loo = e / (1 - h)
            print(f"c_v {cv:5.1f}  {name:9s} R2 {1 - e @ e / sst:.4f}  LOO {1 - loo @ loo / sst:.4f}  "
                  f"share {b[0]:.3f}  coefficient {b[1]:.4g}")


if __name__ == "__main__":
    main()
