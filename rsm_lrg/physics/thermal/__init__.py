"""Thermal models of the THK SHS15V linear rolling guide (paper Eqs. 4, 6-7, 9, 11-12, 18).

- :mod:`.geometry`  catalogue geometry, materials (Table 2), assumptions, voxelisation
- :mod:`.fv`        3-D finite-volume solver of Eq. 7: steady (sparse direct / CG) and
                    implicit transient (one factorisation, many steps)
- :mod:`.network`   reduced network (lumped carriage, ball rows, 1-D rail fin), exact unit
                    responses for vectorised use (``network_response``, ``network_rise``)
- :mod:`.summary`   ``thermal_summary``: the numbers the paper reports (Section 3.1, Fig. 5)
"""

from typing import TYPE_CHECKING, Any

from .geometry import ASSUMPTIONS, GuideGeometry, VoxelModel, voxelise
from .network import ThermalNetwork, fin_conductance, network_response, network_rise

if TYPE_CHECKING:
    from .fv import FVSystem, SteadyResult, TransientResult, time_to_fraction
    from .summary import PAPER_STEADY_RISE_K, ThermalSummary, thermal_summary

#: Names of the finite-volume solver and the summary, imported on first use: they need
#: ``scipy.sparse`` (about 0.2 s of CPU), which the surrogate's network (``rsm-lrg simulate``)
#: does not.
_LAZY = {"FVSystem": ".fv", "SteadyResult": ".fv", "TransientResult": ".fv", "time_to_fraction": ".fv",
         "PAPER_STEADY_RISE_K": ".summary", "ThermalSummary": ".summary", "thermal_summary": ".summary"}


def __getattr__(name: str) -> Any:
    if name in _LAZY:
        from importlib import import_module

        value = getattr(import_module(_LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = [
    "ASSUMPTIONS", "FVSystem", "GuideGeometry", "PAPER_STEADY_RISE_K", "SteadyResult",
    "ThermalNetwork", "ThermalSummary", "TransientResult", "VoxelModel", "fin_conductance",
    "network_response", "network_rise", "thermal_summary", "time_to_fraction", "voxelise",
]


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
