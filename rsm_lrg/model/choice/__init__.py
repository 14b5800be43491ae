"""Model choice: which terms and which order the data support.

``summary`` (Design-Expert's fit summary), ``reduce`` and ``mixed_reduce`` (backward
elimination by p or AICc; by Kenward–Roger p on a REML fit), ``select`` (forward, backward,
stepwise, all hierarchical subsets) and ``loo_compare`` (a Gaussian process beside the
polynomial orders by leave-one-out).
"""
