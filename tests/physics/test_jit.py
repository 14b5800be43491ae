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


def test_one_row_simulate_runs_without_numba_and_equals_the_compiled_row(tmp_path):
    # a one-row design: no numba, no SciPy at all; every column equal, to the last bit, to the
    # same row run compiled (a two-row design with it, in this process: numba)
    design = tmp_path / "row.csv"
    design.write_text("thickness_m,stroke_m,velocity_m_s,acceleration_m_s2\n0.0003,0.04,0.4,30\n")
    out = _run(
        "import json, sys\n"
        "from rsm_lrg.cli import main\n"
        f"status = main(['simulate', {str(design)!r}, '--seed', '1', '-o', {str(tmp_path / 'one.csv')!r}])\n"
        "print(json.dumps({'status': status, 'numba': 'numba' in sys.modules, "
        "'scipy': sorted(k for k in sys.modules if k.startswith('scipy'))}))\n")
    assert out == {"status": 0, "numba": False, "scipy": []}
    import pandas as pd

    from rsm_lrg.surrogate import simulate

    two = simulate(pd.concat([pd.read_csv(design)] * 2, ignore_index=True), seed=1, progress=False)
    one = simulate(pd.read_csv(design), seed=1, progress=False)
    assert "numba" in sys.modules  # two rows ran compiled here
    # the CLI's file holds 10 digits: compare the library's rows at full precision instead
    row = _run(
        "import json, sys\n"
        "import pandas as pd\n"
        "from rsm_lrg.surrogate import simulate\n"
        f"r = simulate(pd.read_csv({str(design)!r}), seed=1, progress=False)\n"
        "print(json.dumps({'numba': 'numba' in sys.modules, 'row': [float(v) for v in "
        "r.select_dtypes('number').iloc[0]]}))\n")
    assert row["numba"] is False
    assert row["row"] == [float(v) for v in two.select_dtypes("number").iloc[0]]
    assert row["row"] == [float(v) for v in one.select_dtypes("number").iloc[0]]  # here numba is loaded


#: Rows for the bit-for-bit check of the interpreted kernels: Table 4's first run, an RMS row, an
#: S-curve stroke, and a 0.15 mm row whose stick-slip does not settle in 40 cycles (benchmarks/
#: bench_simulate.compare_rows(60), row 29): a last-bit difference anywhere moves it by percents.
_ROWS = ("thickness_m,stroke_m,velocity_m_s,acceleration_m_s2,stage,jerk_time_s\n"
         "0.0003,0.04,0.4,30,rfcms,0\n"
         "0.0002,0.05,0.55,35,rms,0\n"
         "0.0004,0.045,0.5,25,rfcms,0.012\n")


def test_interpreted_kernels_equal_the_compiled_ones_bit_for_bit(tmp_path):
    import sys as _sys

    _sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        from bench_simulate import compare_rows
    finally:
        _sys.path.remove(str(ROOT / "benchmarks"))
    import pandas as pd

    from rsm_lrg.surrogate import simulate

    rows = pd.concat([pd.read_csv(__import__("io").StringIO(_ROWS)), compare_rows(60).iloc[[29]]],
                     ignore_index=True)
    path = tmp_path / "rows.csv"
    rows.to_csv(path, index=False, float_format="%.17g")
    rows = pd.read_csv(path)
    compiled = [simulate(rows, seed=3, progress=False, calibration=cal) for cal in ("default", None)]
    out = _run(
        "import json, sys\n"
        "import pandas as pd\n"
        "from rsm_lrg.physics import jit\n"
        "jit.INTERPRETED_MAX_ROWS = 100\n"
        "from rsm_lrg.surrogate import simulate\n"
        f"d = pd.read_csv({str(path)!r})\n"
        "res = []\n"
        "for c in ('default', None):\n"
        "    jit._SPENT = False  # each call interpreted (a process runs only its first batch so)\n"
        "    res.append(simulate(d, seed=3, progress=False, calibration=c).select_dtypes('number').to_numpy().tolist())\n"
        "print(json.dumps({'numba': 'numba' in sys.modules, 'res': res}))\n")
    assert out["numba"] is False
    for got, want in zip(out["res"], compiled):
        assert got == want.select_dtypes("number").to_numpy().tolist()


def test_run_kernel_hands_a_raising_kernel_back_with_its_arrays_restored():
    import numpy as np

    from rsm_lrg.physics import jit

    calls = []

    def python(a, out):
        out[:] = -1.0  # written before it fails: must not reach the compiled call
        a[0] = 99.0
        raise ZeroDivisionError("float division by zero")

    def compiled():
        def kernel(a, out):
            calls.append((a.copy(), out.copy()))
            out[:] = a * 2
        return kernel

    a, out = np.array([1.0, 2.0]), np.zeros(2)
    token = jit._INTERPRETED.set(True)
    try:
        if "numba" in sys.modules:  # interpreted() is False once numba is loaded: force it here
            saved = sys.modules.pop("numba")
        else:
            saved = None
        try:
            jit.run_kernel(python, compiled, a, out)
        finally:
            if saved is not None:
                sys.modules["numba"] = saved
    finally:
        jit._INTERPRETED.reset(token)
    assert [x.tolist() for x in calls[0]] == [[1.0, 2.0], [0.0, 0.0]]
    assert out.tolist() == [2.0, 4.0]


def test_a_hypot_beyond_the_plain_formula_runs_compiled():
    # Python's math.hypot is not the C library's: uncompiled, _fo_hypot hands a pair beyond
    # [1e-150, 1e150] to numba (the eigen-solvers call it), and a plain pair stays uncompiled
    from rsm_lrg.physics.thermal import fixed_order

    out = _run(
        "import json, sys\n"
        "from rsm_lrg.physics.jit import few_rows\n"
        "from rsm_lrg.physics.thermal import fixed_order as fo\n"
        "with few_rows(1):\n"
        "    plain = fo._run('_fo_hypot', 3.0, 4.0)\n"
        "    before = 'numba' in sys.modules\n"
        "    far = [fo._run('_fo_hypot', x, y) for x, y in ((3e200, 4e200), (1e-160, 7e-161))]\n"
        "print(json.dumps({'before': before, 'numba': 'numba' in sys.modules, 'plain': plain, 'far': far}))\n")
    assert out["before"] is False and out["numba"] is True
    assert out["plain"] == 5.0
    hypot = fixed_order._kernels()["_fo_hypot"]
    assert out["far"] == [hypot(3e200, 4e200), hypot(1e-160, 7e-161)]


def test_only_the_first_small_batch_of_a_process_runs_interpreted():
    # a process evaluating row after row pays numba's start-up once, not the interpreted cost per row
    out = _run(
        "import json, sys\n"
        "from rsm_lrg.physics.jit import few_rows, interpreted\n"
        "seen = []\n"
        "for rows in (2, 1, 1):\n"
        "    with few_rows(rows):\n"
        "        seen.append(interpreted())\n"
        "print(json.dumps(seen))\n")
    assert out == [False, True, False]
