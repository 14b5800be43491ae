"""The compiled stick-slip stepper (issue 24, Build item 4): agreement with the event-driven
reference to 1e-6 relative, a row's result independent of its batch (bit for bit), and the
earlier fixed-step integrator kept as the benchmark's anchor."""

from __future__ import annotations

import numpy as np
import pytest

from rsm_lrg.physics import dynamics
from rsm_lrg.physics.params import LRGParams


@pytest.mark.slow
@pytest.mark.parametrize("y, membrane, cv, motion", [
    (1e-4, True, 2.5, (0.04, 0.4, 40.0)), (3e-4, True, 0.0, (0.05, 0.5, 30.0)),
    (5e-4, True, 5.0, (0.06, 0.6, 20.0)), (3e-4, False, 2.5, (0.075, 0.5, 10.0)),
])
def test_sliding_and_viscous_work_match_the_reference(y, membrane, cv, motion):
    # Reference: simulate_stage, DOP853 rtol 1e-10 with exact stop/breakaway events, the same
    # 5 cycles from rest; cycle_metrics reports the mean of the last two cycles. Sliding 1e-6
    # relative (issue 24), viscous work 2e-3 where the cycles have settled (the reference reports
    # its last cycle's), peak deflection 2 % (the reference samples 2000 points per cycle).
    s, v, a = motion
    p = LRGParams(hinge_thickness_m=y, hinge_membrane=membrane, viscous_friction_n_s_m=cv)
    ref = dynamics.simulate_stage(p, n_cycles=5, stroke=s, velocity=v, acceleration=a, rtol=1e-10)
    got = dynamics.cycle_metrics(s, v, a, params=p, method="integrate", n_cycles=5, max_cycles=5)
    r = ref.sliding_per_cycle_m
    assert float(got.sliding_distance_m) == pytest.approx(0.5 * (r[-1] + r[-2]), rel=1e-6)
    if cv > 0 and abs(r[-1] - r[-2]) < 1e-5 * r[-1]:  # the reference gives its last cycle's viscous work
        assert float(got.viscous_work_j) == pytest.approx(ref.viscous_work_j, rel=2e-3)
    assert float(got.peak_deflection_m) == pytest.approx(ref.peak_deflection_m, rel=0.02)


def test_a_row_does_not_depend_on_its_batch():
    rng = np.random.default_rng(4)
    n = 40
    y = rng.uniform(1e-4, 5e-4, n)
    s, v, a = rng.uniform(0.04, 0.06, n), rng.uniform(0.4, 0.6, n), rng.uniform(20, 40, n)
    p = LRGParams(viscous_friction_n_s_m=2.5)
    batch = dynamics.cycle_metrics(s, v, a, params=p, method="integrate", hinge_thickness_m=y)
    for i in (0, 17, 39):
        one = dynamics.cycle_metrics(s[i], v[i], a[i], params=p, method="integrate", hinge_thickness_m=y[i])
        for f in ("sliding_distance_m", "peak_deflection_m", "viscous_work_j", "periodicity_error_m"):
            assert float(np.asarray(getattr(one, f))) == getattr(batch, f)[i], f
    rev = dynamics.cycle_metrics(s[::-1], v[::-1], a[::-1], params=p, method="integrate", hinge_thickness_m=y[::-1])
    assert np.array_equal(rev.sliding_distance_m[::-1], batch.sliding_distance_m)


def test_fixed_step_anchor_agrees_and_bad_integrator_is_refused():
    p = LRGParams(hinge_thickness_m=3e-4, viscous_friction_n_s_m=2.5)
    new = dynamics.cycle_metrics(0.05, 0.5, 30.0, params=p, method="integrate")
    old = dynamics.cycle_metrics(0.05, 0.5, 30.0, params=p, method="integrate", integrator="fixed_step")
    assert float(old.sliding_distance_m) == pytest.approx(float(new.sliding_distance_m), rel=2e-4)
    with pytest.raises(ValueError, match="integrator must be"):
        dynamics.cycle_metrics(0.05, 0.5, 30.0, params=p, integrator="rk4")


def test_a_leaf_beyond_the_tabulated_law_is_refused():
    # a 0.01 mm leaf under the paper's load swings by hundreds of thicknesses: refused, never NaN
    p = LRGParams(hinge_thickness_m=1e-5, hinge_length_m=0.05)
    with pytest.raises(ValueError, match="thicknesses|steps per cycle"):
        dynamics.cycle_metrics(0.06, 0.6, 40.0, params=p, method="integrate")


def _box_rows(n, seed):
    # random settings of the Table 3 box and its 16 corners
    rng = np.random.default_rng(seed)
    lo, hi = np.array([1e-4, 0.04, 0.4, 20.0]), np.array([5e-4, 0.06, 0.6, 40.0])
    corners = np.array([[lo[j] if (i >> j) & 1 == 0 else hi[j] for j in range(4)] for i in range(16)])
    return np.vstack([corners, rng.uniform(lo, hi, (n, 4))])


def test_adaptive_stepper_equals_the_fixed_step_reference_on_the_box():
    # Issue 24, Build item 4: the step-size-controlled stepper (the default) against the DOP853
    # stepper in equal steps (integrator="compiled", the reference), the calibrated viscous
    # friction, 60 random settings of the Table 3 box and its 16 corners, every row integrated.
    # Sliding and viscous work: 1e-6 relative wherever the reference's cycles have settled (a row
    # that has not, a period-2 or irregular stick-slip after 12 cycles, depends on the last bits
    # of any integration: there both integrators differ from a finer reference by as much as from
    # each other). Peak deflection: against the reference at a step 4x finer, whose Hermite
    # interpolation of the peak is accurate to about 1e-5 (the reference's own at ω·Δt = 0.6 is
    # 1e-4 to 2e-3 off); the new stepper refines the peak on its dense output.
    X = _box_rows(60, 24)
    y, s, v, a = X.T
    p = LRGParams(viscous_friction_n_s_m=4.32)
    kw = dict(params=p, method="integrate", hinge_thickness_m=y)
    new = dynamics.cycle_metrics(s, v, a, integrator="adaptive", **kw)
    ref = dynamics.cycle_metrics(s, v, a, integrator="compiled", **kw)
    fine = dynamics.cycle_metrics(s, v, a, integrator="compiled", h_rk=0.15, **kw)
    settled = (ref.periodicity_error_m <= 1e-5 * ref.sliding_distance_m) & (
        fine.periodicity_error_m <= 1e-5 * fine.sliding_distance_m)
    assert settled.sum() >= 0.9 * len(s)
    for f in ("sliding_distance_m", "viscous_work_j"):
        np.testing.assert_allclose(getattr(new, f)[settled], getattr(ref, f)[settled], rtol=1e-6, err_msg=f)
        np.testing.assert_allclose(getattr(new, f)[settled], getattr(fine, f)[settled], rtol=1e-6, err_msg=f)
    np.testing.assert_allclose(new.peak_deflection_m[settled], fine.peak_deflection_m[settled], rtol=3e-5)


def test_old_integrator_stays_callable_and_differs_from_the_new_only_in_its_steps():
    p = LRGParams(hinge_thickness_m=2e-4, viscous_friction_n_s_m=4.32)
    new = dynamics.cycle_metrics(0.05, 0.5, 30.0, params=p, method="integrate", integrator="adaptive")
    old = dynamics.cycle_metrics(0.05, 0.5, 30.0, params=p, method="integrate", integrator="compiled")
    assert float(new.sliding_distance_m) == pytest.approx(float(old.sliding_distance_m), rel=1e-6)
    assert float(new.sliding_distance_m) != float(old.sliding_distance_m)  # two integrators, not one


MU_K_ABOVE = dict(hinge_thickness_m=3e-4, viscous_friction_n_s_m=4.32, mu_k=0.04)  # mu_s = 0.03


def test_with_mu_k_above_mu_s_the_frame_holds_mu_k():
    # Filippov: between mu_s F_z and mu_k F_z neither slip direction can start, so the frame
    # stays stuck until the hinge force passes mu_k F_z: the same dynamics, bit for bit, as
    # mu_s raised to mu_k. Before, the integrators chattered between breakaway and stop there
    # (the adaptive one for seconds per row, landing on 0.193 m; simulate_stage never ended).
    raised = LRGParams(**(MU_K_ABOVE | {"mu_s": 0.04}))
    p = LRGParams(**MU_K_ABOVE)
    for integ in ("compiled", "adaptive", "fixed_step"):
        a = dynamics.cycle_metrics(0.04, 0.4, 20.0, params=p, method="integrate", integrator=integ)
        b = dynamics.cycle_metrics(0.04, 0.4, 20.0, params=raised, method="integrate", integrator=integ)
        assert float(a.sliding_distance_m) == float(b.sliding_distance_m), integ
        assert float(a.peak_deflection_m) == float(b.peak_deflection_m), integ
    qs = dynamics.cycle_metrics(0.04, 0.4, 20.0, params=p, method="quasi_static")
    assert float(qs.sliding_distance_m) == float(
        dynamics.cycle_metrics(0.04, 0.4, 20.0, params=raised, method="quasi_static").sliding_distance_m)


def test_with_mu_k_above_mu_s_the_integrators_agree_with_the_event_driven_reference():
    # the three routes at their converged settings: the periodic state of this row (0.0797340 m;
    # the event-driven solve_ivp reference's cycles 4-8 agree to 1e-9)
    p = LRGParams(**MU_K_ABOVE)
    ref = dynamics.simulate_stage(p, n_cycles=6, stroke=0.04, velocity=0.4, acceleration=20.0, rtol=1e-10)
    last = ref.sliding_per_cycle_m[-1]
    assert abs(ref.sliding_per_cycle_m[-2] - last) < 1e-8 * last
    conv = dict(params=p, method="integrate", rtol=1e-10, max_cycles=40)
    fixed = dynamics.cycle_metrics(0.04, 0.4, 20.0, integrator="compiled", h_rk=0.2, **conv)
    adaptive = dynamics.cycle_metrics(0.04, 0.4, 20.0, integrator="adaptive", tol_rk=1e-9, **conv)
    for got in (fixed, adaptive):
        assert float(got.sliding_distance_m) == pytest.approx(last, rel=1e-6)
    assert float(adaptive.peak_deflection_m) == pytest.approx(float(fixed.peak_deflection_m), rel=1e-5)
    assert float(adaptive.viscous_work_j) == pytest.approx(float(fixed.viscous_work_j), rel=1e-6)


def test_converged_integrators_reach_the_same_periodic_state():
    # Both integrators run to the periodic state itself (successive cycles within 1e-10, at most
    # 40 cycles): the reference at a 12x finer step (omega dt = 0.05; at 0.2 its viscous work on
    # the linear hinge is still 4e-6 off, converging towards the adaptive stepper's as the step
    # shrinks) and the adaptive one at tol 1e-9 agree to 1e-6 in sliding and viscous work, 5e-5
    # in the peak, on box rows (corners and random), S-curve strokes and the linear hinge. The default
    # criterion (1e-5 between successive cycles, at least 3) stops short of it: up to ~3e-3 in
    # sliding on some rows of the box (the report of issue 24), so it is not the reference here.
    X = _box_rows(12, 31)
    y, s, v, a = X.T
    tj = np.where(np.arange(len(s)) % 2 == 1, 0.01, 0.0)
    for p in (LRGParams(viscous_friction_n_s_m=4.32), LRGParams(viscous_friction_n_s_m=4.32, hinge_membrane=False)):
        kw = dict(params=p, method="integrate", hinge_thickness_m=y, jerk_time_s=tj, rtol=1e-10, max_cycles=40)
        ref = dynamics.cycle_metrics(s, v, a, integrator="compiled", h_rk=0.05, **kw)
        new = dynamics.cycle_metrics(s, v, a, integrator="adaptive", tol_rk=1e-9, **kw)
        settled = ref.periodicity_error_m <= 1e-9 * ref.sliding_distance_m
        assert settled.sum() >= 0.8 * len(s)
        for f in ("sliding_distance_m", "viscous_work_j"):
            np.testing.assert_allclose(getattr(new, f)[settled], getattr(ref, f)[settled], rtol=1e-6, err_msg=f)
        np.testing.assert_allclose(new.peak_deflection_m[settled], ref.peak_deflection_m[settled], rtol=5e-5)


@pytest.mark.parametrize("integrator", ["compiled", "adaptive"])
def test_a_row_does_not_depend_on_how_the_batch_is_split(integrator):
    X = _box_rows(30, 8)
    y, s, v, a = X.T
    kw = dict(params=LRGParams(viscous_friction_n_s_m=4.32), method="integrate", integrator=integrator)
    whole = dynamics.cycle_metrics(s, v, a, hinge_thickness_m=y, **kw)
    parts = [dynamics.cycle_metrics(s[i:j], v[i:j], a[i:j], hinge_thickness_m=y[i:j], **kw)
             for i, j in ((0, 7), (7, 8), (8, 46))]
    for f in ("sliding_distance_m", "peak_deflection_m", "viscous_work_j", "periodicity_error_m"):
        assert np.array_equal(np.concatenate([getattr(q, f) for q in parts]), getattr(whole, f)), f


@pytest.mark.slow
def test_both_kernels_load_from_numba_disk_cache():
    # a kernel built from closures is compiled anew in every process (~7 s, every pool worker);
    # the module-level kernels are compiled once and loaded from numba's cache afterwards
    import subprocess
    import sys

    code = ("import numpy as np\nfrom rsm_lrg.physics import dynamics, stepper\n"
            "for i in ('compiled', 'adaptive'):\n"
            "    dynamics.cycle_metrics(0.05, 0.5, 30.0, method='integrate', integrator=i)\n"
            "print(len(stepper._kernel().stats.cache_hits), len(stepper._adaptive_kernel().stats.cache_hits))\n")
    for _ in range(2):
        out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    fixed_hits, adaptive_hits = map(int, out.split())
    assert fixed_hits >= 1 and adaptive_hits >= 1


def test_integrate_rows_reports_cycles_and_steps():
    from rsm_lrg.physics import stepper

    X = _box_rows(12, 2)[16:]  # random rows (distinct strokes), in the order cycle_metrics integrates them
    y, s, v, a = X[np.argsort(X[:, 1])].T
    p = LRGParams(viscous_friction_n_s_m=4.32)
    seen = {}
    got = {}
    original = stepper.integrate_rows

    def spy(*args, **kwargs):
        info = {}
        res = original(*args, **kwargs, info=info)
        seen[kwargs["method"]] = info
        return res

    dynamics.integrate_rows = spy
    try:
        for integ in ("compiled", "adaptive"):
            got[{"compiled": "fixed"}.get(integ, integ)] = dynamics.cycle_metrics(
                s, v, a, params=p, method="integrate", integrator=integ, hinge_thickness_m=y, n_cycles=3, max_cycles=7)
    finally:
        dynamics.integrate_rows = original
    for method, info in seen.items():
        m = got[method]
        assert ((info["cycles"] >= 3) & (info["cycles"] <= 7)).all(), method
        # a row that stopped before max_cycles met the criterion; one that did not ran them all
        unsettled = m.periodicity_error_m > 1e-5 * m.sliding_distance_m
        assert np.array_equal(unsettled, unsettled & (info["cycles"] == 7)), method
        if method == "adaptive":
            assert (info["steps"] > 0).all()
        else:
            assert (info["steps"] == 0).all()
    assert set(seen) == {"fixed", "adaptive"}
