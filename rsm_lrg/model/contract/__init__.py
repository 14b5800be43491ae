"""The prediction contract and the statistics every kind of fit shares.

``prediction`` (:class:`~rsm_lrg.model.contract.prediction.FittedModel`, a ``typing.Protocol``,
and :class:`~rsm_lrg.model.contract.prediction.IntervalForm`: how the standard error, the
variance of a new run and their degrees of freedom follow from a model row, for every kind),
``statistics`` (the t and F tails, the fit statistics under the ANOVA) and ``tolerance``
(regression tolerance intervals). The engines produce interval forms; the results, the
optimisers and the faces read them.
"""
