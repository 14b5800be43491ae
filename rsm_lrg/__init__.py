"""rsm-lrg: design of experiments and response-surface methodology for the linear rolling
guide (LRG) study of Su, Zhang & Yang (2023), *Machines* 11(3), 358.

Layers, each importing only from those before it (checked by import-linter; the contract is
``[tool.importlinter]`` in pyproject.toml, run ``lint-imports``)::

    base (factors, io, present, datasets, registry) -> physics -> surrogate
    base -> design -> model -> optimize -> report -> paper -> cli

``paper`` is the reproduction of Su, Zhang & Yang: it coordinates the physics, the
surrogate, the model and the report; the report only presents.

The names below are imported lazily, so ``import rsm_lrg`` (and ``rsm-lrg --help``) stays
fast and does not pull in numpy, pandas, statsmodels, scipy or matplotlib.

``rsm_lrg.optimize`` is always the package :mod:`rsm_lrg.optimize`, whatever was imported
first; the package is callable, ``rsm_lrg.optimize(result, goal="minimize")`` calls
:func:`rsm_lrg.optimize.optimize` (the function).

``FitResult.optimize``, ``FitResult.to_html`` and ``FitResult._repr_html_`` are
conveniences: the model layer looks the function up in :mod:`rsm_lrg.registry`, and this
facade, above every layer, declares which layer provides it (below).
"""

from __future__ import annotations

import importlib

from . import registry as _registry

__version__ = "0.1.0"  # the one version source: pyproject.toml reads it ([tool.setuptools.dynamic])

# public name -> module that defines it
_LAZY = {
    "Factor": "rsm_lrg.factors",
    "FactorSpace": "rsm_lrg.factors",
    "load_table4": "rsm_lrg.datasets",
    "load_table3": "rsm_lrg.datasets",
    "load_table5": "rsm_lrg.datasets",
    "load_equation19": "rsm_lrg.datasets",
    "load_mixture_etch": "rsm_lrg.datasets",
    "load_cake_split_plot": "rsm_lrg.datasets",
    "read_table": "rsm_lrg.io",
    "ColumnTable": "rsm_lrg.table",
}


def _register(module: str, *names: str) -> None:
    for n in names:
        _LAZY[n] = module


# Filled in by the layers as they land (kept here so the top-level API is in one place).
_register("rsm_lrg.design", "Design", "box_behnken", "central_composite", "full_factorial", "read_design")
_register("rsm_lrg.design", "optimal", "augment", "Constraints", "definitive_screening", "fractional_factorial",
          "plackett_burman", "latin_hypercube", "sobol")
_register("rsm_lrg.design", "simplex_lattice", "simplex_centroid", "extreme_vertices", "MixtureDesign", "split_plot",
          "split_plot_ccd", "split_split_plot", "strip_plot", "mixture_optimal", "cross_process")
_register("rsm_lrg.model", "fit", "FitResult", "ModelSpec", "Transform")
_register("rsm_lrg.optimize", "optimize", "OptimumResult")
_register("rsm_lrg.surrogate", "simulate", "calibrate", "Calibration")
_register("rsm_lrg.model.choice.summary", "fit_summary")
_register("rsm_lrg.model.choice.reduce", "reduce_terms")
_register("rsm_lrg.model.results.glm_result", "GLMResult")
_register("rsm_lrg.model.pipelines.glm", "SeparationError")
_register("rsm_lrg.model.readings.ridge", "ridge")
_register("rsm_lrg.model.readings.mixture_trace", "mixture_trace", "MixtureTrace")
_register("rsm_lrg.model.fit", "fit_transformed")
_register("rsm_lrg.model.dispersion", "fit_dispersion", "DispersionFit")
_register("rsm_lrg.model.evaluate", "evaluate_design", "compare_designs")
_register("rsm_lrg.model.power", "simulate_power", "PowerSimulation")
_register("rsm_lrg.model.readings.effects", "screening_effects", "EffectsResult")
_register("rsm_lrg.optimize.confirm", "confirm")
_register("rsm_lrg.optimize.desirability", "optimize_desirability", "ResponseGoal")
_register("rsm_lrg.optimize.next_runs", "suggest", "Suggestion")
_register("rsm_lrg.physics.chain", "physics_chain", "PhysicsResult")
_register("rsm_lrg.physics.params", "LRGParams")

# The higher layers provide the model's conveniences (resolved on first use).
_registry.register("fit", "rsm_lrg.model.fit:fit")  # FitResult.reduce refits through it
_registry.register("FitResult.optimize", "rsm_lrg.optimize.single:optimize")
_registry.register("FitResult.to_html", "rsm_lrg.report.fit_report:to_html")
_registry.register("FitResult.notebook_html", "rsm_lrg.report.fit_report:notebook_html")
_registry.register("FitResult.profiler", "rsm_lrg.report.interactive:profiler")

#: Top-level names that are sub-packages as well: always the (callable) package.
_PACKAGES = {"optimize"}

__all__ = sorted(_LAZY) + ["__version__"]


def __getattr__(name: str):
    mod = _LAZY.get(name)
    if mod is None:
        raise AttributeError(f"module 'rsm_lrg' has no attribute {name!r}")
    if name in _PACKAGES:
        value = importlib.import_module(f"{__name__}.{name}")
    else:
        value = getattr(importlib.import_module(mod), name)
    globals()[name] = value
    return value


def __dir__():
    return __all__
