"""A mixture: the plasma etch blends, a special cubic and its constrained maximum

Fourteen blends of three components (Myers & Montgomery, *Response Surface Methodology*, 2002,
Table 12.4; R mixexp's ``etch``). The Scheffé special-cubic model is fitted on L-pseudo
components and its maximum sought over the simplex with the third component at least 0.3.
"""
import rsm_lrg

etch = rsm_lrg.load_mixture_etch()
fit = rsm_lrg.fit(etch, "erate", components=["x1", "x2", "x3"], model="special-cubic")
print(fit.summary())

best = rsm_lrg.optimize(fit, goal="maximize", constraints=["x3 >= 0.3"])
print(best.summary())
