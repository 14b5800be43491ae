"""The paper's physics on SI floats and NumPy arrays (knows nothing of statistics).

Modules, named after the physics (one function per equation of Su, Zhang & Yang 2023):

- :mod:`.params`      parameters with units and sources (``data/lrg_shs15v.toml``)
- :mod:`.hinge`       flexure hinge stiffness and deflection, maximum static friction (Eqs. 1-2)
- :mod:`.heat`        friction heat and heat-source intensity (Eqs. 8-9)
- :mod:`.convection`  Reynolds, Prandtl, Nusselt, convection coefficients (Eqs. 10-12)
- :mod:`.wear`        Archard wear, ball contact force, Brinell hardness (Eqs. 13-17)
- :mod:`.tcr`         temperature change rate (Eq. 18)
- :mod:`.motion`      reciprocating trapezoidal motion profile (Eqs. 15-16)
- :mod:`.dynamics`    two-mass RFCMS with stick-slip friction; RMS as the stiff limit (Fig. 1b)
- :mod:`.thermal`     3-D finite volume and reduced network (Eqs. 6-7)
- :mod:`.chain`       the whole chain behind ``rsm-lrg physics``
"""
