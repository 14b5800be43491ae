"""Per-row random streams for the virtual rig's reading noise.

Every design row gets its own stream, a pure function of the seed and the row's index in the
design, so a run's noise does not depend on how the rows are chunked, how many workers run
them, or which executor does (local processes, a Dask cluster, or none).

How the streams are made
------------------------
The seed goes through :class:`numpy.random.SeedSequence` once, giving a 128-bit key. The
stream of row ``i`` is the counter-based generator Philox4x64-10 (Salmon et al., *Parallel
random numbers: as easy as 1, 2, 3*, SC'11; the bit generator behind
:class:`numpy.random.Philox`) under that key, with counters ``(k, i, 0, 0)`` for the k-th
block of the row. Block ``k`` gives the two thermocouple readings of minute ``k``: four
64-bit words, the first two turned into a pair of standard normals by Box–Muller.

Because the generator is counter-based, the noise of reading ``k`` of row ``i`` is computed
directly, for all rows at once, in NumPy; no Python call per row. The words equal those of
``numpy.random.Philox(key=key, counter=[k - 1, i, 0, 0]).random_raw(4)`` (NumPy increments
the counter before each block), which the tests check.

>>> z = reading_noise(seed=7, rows=[0, 1, 2], readings=[0, 50])
>>> z.shape
(3, 2, 2)
>>> bool((reading_noise(7, [2], [0, 50]) == z[2:]).all())   # row 2 alone: same numbers
True
"""

from __future__ import annotations

import numpy as np

from ..errors import ParameterError

__all__ = ["seed_key", "philox4x64", "uniforms", "reading_noise", "resolve_seed"]

_M0 = np.uint64(0xD2E7470EE14C6C93)
_M1 = np.uint64(0xCA5A826395121157)
_W0 = np.uint64(0x9E3779B97F4A7C15)
_W1 = np.uint64(0xBB67AE8584CAA73B)
_LO32 = np.uint64(0xFFFFFFFF)
_S32 = np.uint64(32)


def resolve_seed(seed) -> int:
    """An integer seed from ``None`` (fresh OS entropy), an int, a SeedSequence or a Generator.

    A :class:`numpy.random.Generator` is advanced by one draw; ``None`` draws fresh entropy,
    so the run is not reproducible unless the returned integer is kept.
    """
    if seed is None:
        return int(np.random.SeedSequence().generate_state(1, np.uint64)[0] >> np.uint64(1))
    if isinstance(seed, np.random.Generator):
        return int(seed.integers(0, 2**63))
    if isinstance(seed, np.random.SeedSequence):
        return int(seed.generate_state(1, np.uint64)[0])
    if isinstance(seed, (bool, np.bool_)):
        raise TypeError(f"seed must be an integer, a numpy Generator or None, not {seed!r}")
    if isinstance(seed, (int, np.integer)):
        if seed < 0:
            raise ParameterError("seed", f"seed must be a non-negative integer, got {seed}")
        return int(seed)
    raise TypeError(f"seed must be an integer, a numpy Generator or None, not {type(seed).__name__}")


def seed_key(seed: int) -> np.ndarray:
    """The 128-bit Philox key of a seed: ``SeedSequence(seed).generate_state(2, uint64)``."""
    return np.random.SeedSequence(int(seed)).generate_state(2, np.uint64)


def _mulhilo(a: np.ndarray, b: np.uint64):
    """High and low 64-bit words of the 128-bit product ``a * b`` (element-wise)."""
    lo = a * b
    a_lo, a_hi = a & _LO32, a >> _S32
    b_lo, b_hi = b & _LO32, b >> _S32
    p0 = a_lo * b_lo
    p1 = a_lo * b_hi
    p2 = a_hi * b_lo
    p3 = a_hi * b_hi
    mid = (p0 >> _S32) + (p1 & _LO32) + (p2 & _LO32)
    hi = p3 + (p1 >> _S32) + (p2 >> _S32) + (mid >> _S32)
    return hi, lo


def philox4x64(counter: np.ndarray, key: np.ndarray, rounds: int = 10) -> np.ndarray:
    """Philox4x64 block function, vectorised.

    Parameters
    ----------
    counter : (..., 4) uint64 array
        One 256-bit counter per block.
    key : (2,) uint64 array
        The 128-bit key.
    rounds : int
        Number of rounds (10, as in Random123 and NumPy).

    Returns
    -------
    (..., 4) uint64 array of random words.
    """
    c = np.asarray(counter, dtype=np.uint64)
    c0, c1, c2, c3 = (c[..., j].copy() for j in range(4))
    k0, k1 = np.uint64(key[0]), np.uint64(key[1])
    with np.errstate(over="ignore"):
        for r in range(rounds):
            if r:
                k0 = np.uint64(k0 + _W0)
                k1 = np.uint64(k1 + _W1)
            hi0, lo0 = _mulhilo(c0, _M0)
            hi1, lo1 = _mulhilo(c2, _M1)
            c0, c1, c2, c3 = hi1 ^ c1 ^ k0, lo1, hi0 ^ c3 ^ k1, lo0
    return np.stack([c0, c1, c2, c3], axis=-1)


def uniforms(seed: int, rows, blocks) -> np.ndarray:
    """Uniform doubles in [0, 1): shape ``(len(rows), len(blocks), 4)``.

    Word ``j`` of block ``k`` of row ``i`` is Philox4x64-10 under :func:`seed_key` at
    counter ``(k, i, 0, 0)``, its top 53 bits scaled by 2**-53 (NumPy's ``random()`` rule).
    """
    rows = np.asarray(rows, dtype=np.uint64).reshape(-1)
    blocks = np.asarray(blocks, dtype=np.uint64).reshape(-1)
    ctr = np.zeros((rows.size, blocks.size, 4), dtype=np.uint64)
    ctr[..., 0] = blocks[None, :]
    ctr[..., 1] = rows[:, None]
    words = philox4x64(ctr, seed_key(seed))
    return (words >> np.uint64(11)).astype(np.float64) * (1.0 / 9007199254740992.0)


def reading_noise(seed: int, rows, readings, n_sensors: int = 2) -> np.ndarray:
    """Standard-normal noise of each thermocouple reading: shape ``(rows, readings, sensors)``.

    Reading ``k`` (minute ``k`` of the test, 0 = start) of row ``i`` uses block ``k`` of the
    row's stream (see the module docstring); Box–Muller on its first two words gives the
    two sensors' values (``n_sensors`` <= 4; sensors 3 and 4 use words 3 and 4).
    """
    if not 1 <= n_sensors <= 4:
        raise ValueError(f"n_sensors must be 1 to 4, got {n_sensors}")
    u = uniforms(seed, rows, readings)
    out = []
    for a, b in ((0, 1), (2, 3))[: (n_sensors + 1) // 2]:
        r = np.sqrt(-2.0 * np.log1p(-u[..., a]))  # 1 - u in (0, 1]: log finite
        th = 2.0 * np.pi * u[..., b]
        out += [r * np.cos(th), r * np.sin(th)]
    return np.stack(out[:n_sensors], axis=-1)
