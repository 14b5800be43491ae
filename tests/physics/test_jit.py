"""numba imported for the physics kernels without SciPy's linear-algebra package
(:mod:`rsm_lrg.physics.jit`), and the thermal package without scipy.sparse; each in a fresh
interpreter (what it has imported is the point)."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _run(code: str) -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return json.loads(proc.stdout.splitlines()[-1])


def test_a_kernel_loads_without_scipy_linalg_and_blas_still_works():
    pytest.importorskip("scipy")
    out = _run(
        "import json, sys, numpy as np\n"
        "from rsm_lrg.physics import leafcore\n"
        "s, d, t = leafcore.leaf_parts(np.array([0.1, 1.0, 30.0]))\n"
        "before = sorted(k for k in sys.modules if k.startswith('scipy.linalg') or k.startswith('scipy.sparse'))\n"
        "from rsm_lrg.physics.jit import import_numba\n"
        "numba = import_numba()\n"
        "dot = numba.njit(lambda a, b: np.dot(a, b))\n"  # a compiled np.dot needs SciPy's BLAS
        "a = np.arange(12.0).reshape(3, 4)\n"
        "ok_dot = bool(np.array_equal(dot(a, a.T), a @ a.T))\n"
        "import scipy.linalg\n"  # the package imports as usual afterwards
        "x = scipy.linalg.solve(np.array([[4.0, 2.0], [2.0, 3.0]]), np.array([2.0, 1.0]))\n"
        "from scipy.linalg import cython_blas\n"
        "print(json.dumps({'before': before, 'dot': ok_dot, 'solve': x.tolist(), "
        "'same_module': cython_blas is sys.modules['scipy.linalg.cython_blas'], "
        "'parts': [float(v) for v in (s[1], d[1], t[1])]}))\n")
    assert out["before"] == ["scipy.linalg.cython_blas"]  # the extension alone, not its package
    assert out["dot"] is True
    assert out["solve"] == [0.5, 0.0]
    assert out["same_module"] is True
    # S(1), D(1)/1 and tanh(1)/1 of hinge's closed forms (leafcore's module docstring)
    import math
    th, ch = math.tanh(1.0), math.cosh(1.0)
    assert out["parts"] == pytest.approx([3 * (1 - th), 1 + 0.5 / ch ** 2 - 1.5 * th, th], rel=1e-15)


def test_thermal_package_defers_the_finite_volume_solver():
    out = _run(
        "import json, sys\n"
        "import rsm_lrg.physics.thermal as thermal\n"
        "before = 'rsm_lrg.physics.thermal.fv' in sys.modules\n"
        "from rsm_lrg.physics.thermal import FVSystem, thermal_summary\n"
        "from rsm_lrg.physics.thermal.fv import FVSystem as direct\n"
        "print(json.dumps({'before': before, 'same': FVSystem is direct, 'summary': thermal_summary.__module__, "
        "'listed': sorted(set(thermal.__all__) - set(dir(thermal)))}))\n")
    assert out == {"before": False, "same": True, "summary": "rsm_lrg.physics.thermal.summary", "listed": []}
    with pytest.raises(AttributeError, match="no attribute 'nothing'"):
        import rsm_lrg.physics.thermal as thermal

        thermal.nothing  # noqa: B018


def test_simulate_imports_no_scipy_package_beyond_the_blas_extension(tmp_path):
    # issue 37, item 6: a one-row simulate loads neither scipy.interpolate, scipy.integrate,
    # scipy.linalg nor scipy.sparse (the stage integrator's spline and tableau are NumPy's and ours)
    design = tmp_path / "row.csv"
    design.write_text("thickness_m,stroke_m,velocity_m_s,acceleration_m_s2\n0.0003,0.04,0.4,30\n")
    out = _run(
        "import json, sys\n"
        "from rsm_lrg.cli import main\n"
        f"status = main(['simulate', {str(design)!r}, '--seed', '1', '-o', {str(tmp_path / 'runs.csv')!r}])\n"
        "print(json.dumps({'status': status, 'scipy': sorted(k for k in sys.modules if k.startswith('scipy.') "
        "and k.split('.')[1] in ('interpolate', 'integrate', 'linalg', 'sparse', 'optimize', 'special'))}))\n")
    assert out["status"] == 0
    assert out["scipy"] in ([], ["scipy.linalg.cython_blas"])
