"""The report layer: text, HTML and figures of result objects. Its only computation is what it
asks the layers below for: the optima the interactive page offers (:mod:`rsm_lrg.optimize`)
and the numbers of the fitted models (the prediction contract's interval form).

``plots`` (matplotlib figures from arrays, as ``data:`` URIs), ``html`` (the Jinja2
environment, autoescaping on, with the number formats of :mod:`rsm_lrg.present` as
filters), ``fit_report`` (:func:`to_html`, :func:`write_report`: the self-contained HTML
report of a fit; :func:`notebook_html`: the small, figure-free notebook face), ``interactive``
(:func:`interactive_html`, :func:`write_interactive_report`: the page with the prediction
profiler, overlay plot and live surfaces of one or several responses; :func:`profiler`: that
page in a notebook) and
``reproduction_page`` (the terminal table and HTML page of the paper reproduction, which
:mod:`rsm_lrg.paper` computes; the report layer never imports the paper layer).

>>> from rsm_lrg.report import SECTION_IDS
>>> SECTION_IDS[:3]
('summary', 'data', 'anova')
"""

from .fit_report import SECTION_IDS, notebook_html, report_context, to_html, write_report
from .interactive import interactive_html, profiler, write_interactive_report

__all__ = ["to_html", "write_report", "report_context", "notebook_html", "SECTION_IDS", "interactive_html",
           "write_interactive_report", "profiler"]
