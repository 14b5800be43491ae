"""Thermal models of the THK SHS15V linear rolling guide (paper Eqs. 4, 6-7, 9, 11-12, 18).

- :mod:`.geometry`  catalogue geometry, materials (Table 2), assumptions, voxelisation
- :mod:`.fv`        3-D finite-volume solver of Eq. 7: steady (sparse direct / CG) and
                    implicit transient (one factorisation, many steps)
- :mod:`.network`   reduced network (lumped carriage, ball rows, 1-D rail fin), exact unit
                    responses for vectorised use (``network_response``, ``network_rise``)
- :mod:`.summary`   ``thermal_summary``: the numbers the paper reports (Section 3.1, Fig. 5)
"""

from .fv import FVSystem, SteadyResult, TransientResult, time_to_fraction
from .geometry import ASSUMPTIONS, GuideGeometry, VoxelModel, voxelise
from .network import ThermalNetwork, fin_conductance, network_response, network_rise
from .summary import PAPER_STEADY_RISE_K, ThermalSummary, thermal_summary

__all__ = [
    "ASSUMPTIONS", "FVSystem", "GuideGeometry", "PAPER_STEADY_RISE_K", "SteadyResult",
    "ThermalNetwork", "ThermalSummary", "TransientResult", "VoxelModel", "fin_conductance",
    "network_response", "network_rise", "thermal_summary", "time_to_fraction", "voxelise",
]
