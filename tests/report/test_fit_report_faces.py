"""FitResult's HTML faces delegate to the report layer."""

import pytest

import rsm_lrg


@pytest.mark.slow
def test_to_html_and_repr_html_are_the_report():
    r = rsm_lrg.fit(rsm_lrg.load_table4(), "tcr_c_per_min")
    page = r.to_html()
    assert page.lstrip().lower().startswith("<!doctype html")
    assert "26.03" in page  # Table 5: Model F-value
    nb = r._repr_html_()
    assert "221.9" in nb  # Table 5: F of C (221.92), in the notebook face too
