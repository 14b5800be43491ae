"""Per-row random streams (rsm_lrg.surrogate.noise)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from rsm_lrg.surrogate.noise import philox4x64, reading_noise, resolve_seed, seed_key, uniforms


@pytest.mark.parametrize("seed", [0, 1, 2**40 + 7])
@pytest.mark.parametrize("block,row", [(1, 0), (5, 7), (50, 99_999), (3, 2**40)])
def test_philox_matches_numpy_bit_generator(seed, block, row):
    # Independent route: NumPy's own Philox4x64-10 (Salmon et al. 2011). NumPy increments
    # the counter before producing a block, so counter (k-1, i) yields our block (k, i).
    key = seed_key(seed)
    ours = philox4x64(np.array([[block, row, 0, 0]], dtype=np.uint64), key)[0]
    ref = np.random.Philox(key=key, counter=np.array([block - 1, row, 0, 0], dtype=np.uint64)).random_raw(4)
    assert (ours == ref).all()


def test_block_zero_matches_numpy_with_carry():
    key = seed_key(3)
    ours = philox4x64(np.array([[0, 5, 0, 0]], dtype=np.uint64), key)[0]
    ctr = np.array([2**64 - 1, 4, 0, 0], dtype=np.uint64)  # +1 carries into word 1
    assert (ours == np.random.Philox(key=key, counter=ctr).random_raw(4)).all()


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 2**63), rows=st.lists(st.integers(0, 10**9), min_size=1, max_size=20, unique=True),
       split=st.integers(0, 20))
def test_a_rows_noise_does_not_depend_on_the_other_rows(seed, rows, split):
    whole = reading_noise(seed, rows, [0, 7, 50])
    a, b = rows[:split], rows[split:]
    parts = [reading_noise(seed, r, [0, 7, 50]) for r in (a, b) if r]
    assert (np.concatenate(parts) == whole).all()
    # and not on which readings are asked for
    assert (reading_noise(seed, rows, [50])[:, 0] == whole[:, 2]).all()


def test_noise_is_standard_normal_and_independent():
    z = reading_noise(11, np.arange(20000), np.arange(5)).reshape(-1, 2)
    n = z.shape[0]
    # mean 0 and SD 1 within 5 standard errors (normal theory: SE(mean)=1/sqrt(n),
    # SE(sd)~1/sqrt(2n)); correlation of the two sensors within 5/sqrt(n)
    assert abs(z.mean()) < 5 / np.sqrt(z.size)
    assert abs(z.std() - 1) < 5 / np.sqrt(2 * z.size)
    assert abs(np.corrcoef(z[:, 0], z[:, 1])[0, 1]) < 5 / np.sqrt(n)
    # 4th moment of a standard normal is 3 (within 5 SE; var(z^4) = 96)
    assert abs(np.mean(z**4) - 3) < 5 * np.sqrt(96 / z.size)


def test_uniforms_in_unit_interval_and_seeds_differ():
    u = uniforms(1, np.arange(1000), [0, 1])
    assert u.min() >= 0 and u.max() < 1
    assert not np.array_equal(reading_noise(1, [0], [0]), reading_noise(2, [0], [0]))


def test_resolve_seed():
    assert resolve_seed(5) == 5
    g1, g2 = np.random.default_rng(3), np.random.default_rng(3)
    assert resolve_seed(g1) == resolve_seed(g2)
    assert isinstance(resolve_seed(None), int)
    with pytest.raises(ValueError, match="non-negative"):
        resolve_seed(-1)
    with pytest.raises(TypeError):
        resolve_seed(True)
    with pytest.raises(TypeError):
        resolve_seed("7")
