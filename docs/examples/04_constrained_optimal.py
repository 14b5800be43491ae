"""A constrained optimal design: the guide over a wider range, inside s ≥ v²/a

The motion profile reaches velocity v [m/s] within stroke s [m] only when s ≥ v²/a (a the
acceleration [m/s²]), so a wider study of the guide has a region that is not a box. An
I-optimal design for the full quadratic is placed inside it by coordinate exchange; every run
is checked against the constraint below.
"""
import rsm_lrg

factors = {"thickness_m": (0.0001, 0.0005), "stroke_m": (0.02, 0.10),
           "velocity_m_s": (0.2, 1.0), "acceleration_m_s2": (5.0, 40.0)}
constraint = "velocity_m_s**2/acceleration_m_s2 <= stroke_m"
design = rsm_lrg.optimal(factors, model="quadratic", criterion="I", constraints=[constraint], seed=7)
print(design.summary())

runs = design.to_frame()
slack = runs["stroke_m"] - runs["velocity_m_s"] ** 2 / runs["acceleration_m_s2"]
print(f"{len(runs)} runs; smallest s - v^2/a: {slack.min():.3g} m (every run feasible: {bool((slack >= -1e-12).all())})")
