"""The leaf's element-wise kernels (:mod:`rsm_lrg.physics.leafcore`): the NumPy twin that runs a
one-row batch without numba (:mod:`rsm_lrg.physics.jit`) equals the compiled kernels bit for bit."""


def test_leaf_root_solves_in_numpy_equal_the_compiled_ones():
    # the leaf force table's 40,001 solves, random loads and ratios over 16 decades, 0 and tiny
    # values; and S, D/u^4, tanh(u)/u on both branches of the series cut at u = 0.2
    import numpy as np

    from rsm_lrg.physics import hinge, leafcore

    rng = np.random.default_rng(5)
    r = np.arange(0.0, hinge.LEAF_TABLE_MAX_RATIO + 0.005, 0.01)
    q = np.concatenate([r, rng.uniform(0, 5, 5000), 10 ** rng.uniform(-12, 4, 5000), [0.0, 1e-300, 1e-20, np.inf, np.nan]])
    solve = leafcore._kernels()[0]
    for which in (0, 1):
        with np.errstate(all="ignore"):  # inf and nan give inf and nan, as compiled (as _solve calls it)
            ours = leafcore._np_solve(q, which)
        assert np.array_equal(ours, solve(q, which), equal_nan=True)
    u = np.concatenate([rng.uniform(0, 1, 5000), rng.uniform(0, 400, 5000), [0.0, 0.2, 350.0, 1e-5]])
    for ours, compiled in zip(leafcore._np_parts(u), leafcore._kernels()[1](u)):
        assert np.array_equal(ours, compiled)
