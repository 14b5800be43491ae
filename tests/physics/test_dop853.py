"""The DOP853 tableau written out in :mod:`rsm_lrg.physics.dop853` is SciPy's, bit for bit."""

import numpy as np
import pytest

from rsm_lrg.physics import dop853


def test_tableau_equals_scipy_bit_for_bit():
    # Reference: scipy.integrate.DOP853 (its arrays come from scipy's dop853_coefficients.py,
    # the tableau of Hairer, Norsett & Wanner 1993, Section II.10); equal to the last bit
    ref = pytest.importorskip("scipy.integrate").DOP853
    n = dop853.N_STAGES
    pairs = {"A": (dop853.A[:n, :n], ref.A), "B": (dop853.B, ref.B), "C": (dop853.C[:n], ref.C),
             "E3": (dop853.E3, ref.E3), "E5": (dop853.E5, ref.E5), "D": (dop853.D, ref.D),
             "A_EXTRA": (dop853.A[n + 1:], ref.A_EXTRA), "C_EXTRA": (dop853.C[n + 1:], ref.C_EXTRA)}
    for name, (ours, theirs) in pairs.items():
        assert ours.shape == np.shape(theirs), name
        assert ours.tobytes() == np.asarray(theirs, dtype=float).tobytes(), name
    assert (dop853.N_STAGES, dop853.N_STAGES_EXTENDED, dop853.INTERPOLATOR_POWER) == (ref.n_stages, 16, 7)


def test_tableau_is_an_order_8_method():
    # Order conditions that any consistent tableau meets (Hairer et al. II.2): rows of A sum to
    # C, the weights sum to 1, sum b_i c_i^(k-1) = 1/k for k <= 8; a changed digit breaks them
    n = dop853.N_STAGES
    a, b, c = dop853.A[:n, :n], dop853.B, dop853.C[:n]
    np.testing.assert_allclose(a.sum(axis=1), c, rtol=0, atol=1e-14)
    for k in range(1, 9):
        assert abs(float(b @ c ** (k - 1)) - 1.0 / k) < 1e-15
