"""What the Table 4 data ask of a thickness mechanism (issue 4 analysis, not a test).

Model: κ = g(y) · [µ_k·F_z·(2s/T) + c_v·<ẋ²>] — the cycle-averaged Coulomb heat of a carriage
that slides the full stroke plus the viscous heat (Eq. 8 mechanism; T and <ẋ²> from the
trapezoidal profile, rsm_lrg.physics.motion), with a free factor g per hinge thickness level
(three values) and c_v free: the best any thickness mechanism acting as a heat factor could do.

Run: python docs/analysis/thickness_factor.py  (prints R², g ratios, c_v; about 1 s)
Result (2026-11-22): R² 0.867, g(0.1 mm) : g(0.3 mm) : g(0.5 mm) = 0.87 : 1 : 1.08 - nearly
linear in y. With Eq. 1 the hinge compliance goes as y⁻³, so the sliding lost to the hinge,
1 − g, would fall 27-fold from 0.1 to 0.3 mm and 4.6-fold from 0.3 to 0.5 mm: 0.13 then 0.08
of the centre value is out of its reach (the algebra: 1 − r/4.63 = 1.084·(1 − r) gives
r = 0.097 at 0.3 mm and 27·r = 2.6 > 1 at 0.1 mm).
"""

import numpy as np
from scipy.optimize import least_squares

from rsm_lrg.datasets import load_table4
from rsm_lrg.physics import motion
from rsm_lrg.physics.params import LRGParams


def main():
    d = load_table4()
    y, s, v, a, k = (d[c].to_numpy() for c in ("thickness_m", "stroke_m", "velocity_m_s",
                                               "acceleration_m_s2", "tcr_c_per_min"))
    p = LRGParams()
    coulomb = p.mu_k * p.normal_load_n * motion.mean_speed(s, v, a)        # W
    msq = motion.mean_square_speed(s, v, a)                                 # m²/s²
    level = np.searchsorted([1e-4, 3e-4, 5e-4], y - 1e-9)

    def model(th):
        g, cv = np.asarray(th[:3]), th[3]
        return g[level] * (coulomb + cv * msq)

    r = least_squares(lambda th: model(th) - k, [0.01, 0.01, 0.01, 1.0], bounds=(0, np.inf))
    r2 = 1 - np.sum((k - model(r.x)) ** 2) / np.sum((k - k.mean()) ** 2)
    g = r.x[:3] / r.x[1]
    print(f"R2 {r2:.3f}; g(0.1) : g(0.3) : g(0.5) = {g[0]:.3f} : 1 : {g[2]:.3f}; c_v {r.x[3]:.2f} N s/m")


if __name__ == "__main__":
    main()
