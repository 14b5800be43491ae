"""numba for the compiled kernels of the physics (:mod:`.leafcore`, :mod:`.stepper`,
:mod:`.thermal.fixed_order`), imported without SciPy's linear-algebra package.

When numba prepares its first function (compiled or loaded from its disk cache) it checks once
whether a BLAS is available for ``np.dot`` and ``np.linalg`` in compiled code, by importing
``scipy.linalg.cython_blas`` (``numba.np.linalg.ensure_blas``). Importing that extension through
its package runs ``scipy/linalg/__init__.py``, which imports most of ``scipy.linalg``,
``scipy.sparse`` and ``numpy.f2py``: about 0.3 s of CPU, a sixth of a one-row ``rsm-lrg
simulate``, for kernels that call no BLAS. :func:`import_numba` loads the extension module
itself first (the same file, by the ordinary extension loader, under its own name), so numba's
check finds it and the package is imported only if something asks for it. Nothing else changes:
a compiled ``np.dot`` still gets SciPy's BLAS from that module, and a later ``import
scipy.linalg`` imports the package as usual (``tests/physics/test_jit.py``). Where SciPy is
missing, laid out differently or fails to load that way, numba is imported as it always was.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys
from types import ModuleType

__all__ = ["import_numba"]

_CYTHON_BLAS = "scipy.linalg.cython_blas"


def _preload_cython_blas() -> None:
    if _CYTHON_BLAS in sys.modules or "scipy.linalg" in sys.modules:
        return
    try:
        top = importlib.util.find_spec("scipy")
        if top is None or not top.submodule_search_locations:
            return
        spec = importlib.machinery.PathFinder.find_spec(
            _CYTHON_BLAS, [os.path.join(loc, "linalg") for loc in top.submodule_search_locations])
        if spec is None or not isinstance(spec.loader, importlib.machinery.ExtensionFileLoader):
            return
        import scipy  # noqa: F401  (numba's `import scipy.linalg.cython_blas` binds the top package)

        module = importlib.util.module_from_spec(spec)
        sys.modules[_CYTHON_BLAS] = module
        spec.loader.exec_module(module)
    except Exception:  # anything unexpected: numba imports it through the package, as before
        sys.modules.pop(_CYTHON_BLAS, None)


def import_numba() -> ModuleType:
    """The ``numba`` module, imported (on the first call) after SciPy's ``cython_blas`` extension
    has been loaded on its own (see the module docstring).

    Returns
    -------
    module
        ``numba``.
    """
    if "numba.np.arraymath" not in sys.modules:  # numba's check has not run yet
        _preload_cython_blas()
    import numba

    return numba
