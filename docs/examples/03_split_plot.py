"""A split-plot: the cake-baking oven runs, fitted by REML with Kenward–Roger tests

Lawson's cake-baking experiment (daewr ``cakeb``): ``x1`` is set once per oven run (the whole
plot), ``x2`` varies inside it. Ordinary least squares would test ``x1`` against the small
within-oven error; REML with a random intercept per oven run tests it against the oven-to-oven
variation, with Kenward–Roger denominator degrees of freedom.
"""
import rsm_lrg

cake = rsm_lrg.load_cake_split_plot()
fit = rsm_lrg.fit(cake, "y", factors=["x1", "x2"], whole_plot="Ovenrun")
print(fit.summary())
