"""The surrogate: virtual runs of the physics for a few design rows

``simulate`` runs the paper's physics (friction heat, convection, the thermal network, Archard
wear) for each row of a design and adds the responses: the temperature change rate κ
[°C/min], the temperature rise [K] at the end of the test and at steady state, the wear volume
[m³/h] and the sliding distance per cycle [m]. Here: the first four runs of the paper's design,
with the measurement noise switched off.
"""
import warnings

import rsm_lrg

design = rsm_lrg.load_table4().drop(columns=["tcr_c_per_min"]).head(4)
with warnings.catch_warnings():
    warnings.simplefilter("ignore")  # the leaves' yield warnings, explained in the guide
    runs = rsm_lrg.simulate(design, seed=1, noise_sd=0.0)
columns = ["thickness_m", "velocity_m_s", "tcr_c_per_min", "temperature_rise_k", "wear_volume_m3_per_h"]
print(runs[columns].to_string(index=False))
