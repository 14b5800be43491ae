"""The report layer: text, HTML and figures of result objects; it computes nothing of its own.

``plots`` (matplotlib figures from arrays, as ``data:`` URIs), ``html`` (the Jinja2
environment, autoescaping on, and number formats), ``fit_report`` (:func:`to_html`,
:func:`write_report`: the self-contained HTML report of a fit) and ``reproduce`` (the paper
side by side with the toolkit).

>>> from rsm_lrg.report import SECTION_IDS
>>> SECTION_IDS[:3]
('summary', 'data', 'anova')
"""

from .fit_report import SECTION_IDS, report_context, to_html, write_report

__all__ = ["to_html", "write_report", "report_context", "SECTION_IDS"]
