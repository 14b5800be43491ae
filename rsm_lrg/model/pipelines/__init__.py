"""Each kind's fit from built inputs to its result: ``dask_fit`` (a Dask frame partition by
partition), ``glm`` (iteratively reweighted least squares, the analysis of deviance) and ``gp``
(the Gaussian process's likelihood and hyper-parameters). :func:`rsm_lrg.model.fit.fit`
dispatches to them.
"""
