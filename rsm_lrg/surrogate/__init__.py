"""Virtual runs: the physics of :mod:`rsm_lrg.physics` as a response generator.

A design goes in, one row of responses per run comes out, as if the rig of Su, Zhang & Yang
(2023, Section 4) had run it:

- :func:`simulate` (:mod:`.execute`): batches, executors (local processes, Dask), progress;
- :mod:`.runs`: the row model (motion, stage dynamics, friction heat, thermal record, κ by
  Eq. 18, Archard wear), vectorised over rows;
- :mod:`.noise`: per-row random streams for the thermocouple reading noise;
- :mod:`.design_input`: reading and checking a design;
- :mod:`.calibrate`: the calibrated parameters (``data/calibration.toml``), bounded least
  squares and leave-one-out cross-validation;
- :mod:`.progress`: the progress bar on stderr both of them show.
"""

from .calibrate import Calibration, ParameterEstimate, calibrate, load_calibration
from .execute import DEFAULT_NOISE_SD, simulate

__all__ = ["simulate", "calibrate", "Calibration", "ParameterEstimate", "load_calibration", "DEFAULT_NOISE_SD"]
