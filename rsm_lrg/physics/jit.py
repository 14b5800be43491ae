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

**A few rows without numba.** numba's start-up (its import and its first kernel from the disk
cache, about 0.9 s of CPU) is most of a one-row ``simulate``. Inside :func:`few_rows` with at
most :data:`INTERPRETED_MAX_ROWS` rows, while numba is not imported and for the first such batch
of a process only (a process that goes on row after row pays numba's start-up once, not the
interpreted cost every time), the kernels run as plain
Python (:func:`run_kernel`: the same functions numba compiles, called as they are) and the leaf's
root solves as NumPy (:func:`.leafcore.parameter_for_load`'s vectorised twin, the table of
40,001 of them in about 0.09 s). Their results are the compiled ones bit for bit
(``tests/physics/test_jit.py`` compares every column of ``simulate``): numba compiles with
``fastmath`` off, so every ``+``, ``*``, ``/`` and ``sqrt`` is one IEEE-754 operation in both,
``tanh``, ``cosh``, ``expm1`` and ``pow`` are the C library's in both, and the kernels write
``x * x`` where numba would turn ``x ** 2`` into that product. Python raises where compiled code
returns inf or nan (a division by zero): the kernel's arrays are then put back and the compiled
kernel runs. A row costs 0.3 s or more this way, so a design of more than one row runs compiled.
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from types import ModuleType
from typing import Any

import numpy as np

__all__ = ["import_numba", "few_rows", "interpreted", "run_kernel", "INTERPRETED_MAX_ROWS"]

#: Rows of a batch up to which :func:`few_rows` runs the kernels without numba (when numba is not
#: imported yet): interpreted, a row's stage dynamics and rig network cost about 0.3 s of CPU for
#: Table 4's first row and 0.63 s a row on average over the 107 rows of the bit-for-bit check
#: (whose unsettled rows run 40 cycles), against about 0.9 s for numba's start-up.
INTERPRETED_MAX_ROWS = 1

_INTERPRETED: ContextVar[bool] = ContextVar("rsm_lrg_physics_interpreted", default=False)

#: Set by the first batch run interpreted: the next ones run compiled, so that a process that
#: evaluates row after row (a loop of one-row ``simulate`` calls) pays numba's start-up once
#: instead of the interpreted cost on every row.
_SPENT = False


def _spend() -> None:
    global _SPENT
    _SPENT = True

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


@contextmanager
def few_rows(rows: int) -> Iterator[None]:
    """Inside, the kernels run without numba when ``rows`` is at most
    :data:`INTERPRETED_MAX_ROWS`, numba is not imported and no batch of this process ran so
    before (the same numbers; see the module docstring).

    Parameters
    ----------
    rows : int
        Rows of the batch about to be evaluated.

    Returns
    -------
    context manager
        Sets the choice for the calls made inside it (this thread or task only).
    """
    use = rows <= INTERPRETED_MAX_ROWS and "numba" not in sys.modules and not _SPENT
    if use:
        _spend()
    token = _INTERPRETED.set(use)
    try:
        yield
    finally:
        _INTERPRETED.reset(token)


def interpreted() -> bool:
    """Whether a kernel called now runs without numba (inside :func:`few_rows`, numba not
    imported).

    Returns
    -------
    bool
    """
    return _INTERPRETED.get() and "numba" not in sys.modules


def run_kernel(python: Callable[..., Any], compiled: Callable[[], Callable[..., Any]], *args: Any) -> Any:
    """Call a kernel: ``python(*args)`` when :func:`interpreted`, else ``compiled()(*args)``.

    Parameters
    ----------
    python : callable
        The kernel's Python function (what numba compiles).
    compiled : callable
        Returns the compiled kernel (compiling or loading it on the first call).
    *args
        The kernel's arguments; arrays it writes are put back as they were if the Python call
        raises (where compiled code would return inf or nan), before the compiled kernel runs.

    Returns
    -------
    object
        What the kernel returns.
    """
    if interpreted():
        saved = [(a, a.copy()) for a in args if isinstance(a, np.ndarray)]
        try:
            with np.errstate(all="ignore"):
                return python(*args)
        except (ArithmeticError, ValueError, IndexError):
            for a, copy in saved:
                np.copyto(a, copy)
    return compiled()(*args)
