"""Profile-likelihood intervals of every parameter of the shipped calibration (model v5).

``calibrate`` stores the profile interval of the stage parameter (c_v); the heat-balance
parameters (c_d, the ball contacts' conductance) carry the Jacobian's s.e. in the file. This
script computes their 95 % profile intervals on Table 4 with
:func:`rsm_lrg.surrogate.calibrate.profile_interval` (each trial value a least-squares fit of the
others; several minutes on two cores):

    python docs/analysis/profile_v5.py
"""

from __future__ import annotations

from rsm_lrg.datasets import load_table4
from rsm_lrg.surrogate.calibrate import profile_interval, resolve_calibration


def main() -> None:
    cal = resolve_calibration("default")
    t4 = load_table4()
    data = t4[["thickness_m", "stroke_m", "velocity_m_s", "acceleration_m_s2", "tcr_c_per_min"]]
    for q in cal.parameters:
        lo, hi = profile_interval(data, cal, q.name)
        print(f"{q.name:<30} {q.value:.4g} {q.unit}: 95 % profile interval [{lo:.4g}, {hi:.4g}]"
              f"  (Jacobian s.e. {q.std_error:.2g})")


if __name__ == "__main__":
    main()
