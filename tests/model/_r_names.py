"""Names of R's ``lm``/``nlme`` output in this package's terms, for the tests that compare with R
(``test_categoric_r.py``, ``test_mixed_r.py``)."""

import re


def ours(r_name: str, space) -> str:
    """Our column name of an R column (``A:D1`` -> ``AD[north]``, ``I(A^2)`` -> ``A^2``)."""
    if r_name == "(Intercept)":
        return "Intercept"
    num, cat = "", ""
    for part in r_name.split(":"):
        m = re.fullmatch(r"I\(([A-Z])\^2\)", part)
        if m:
            num += f"{m.group(1)}^2"
            continue
        m = re.fullmatch(r"([A-Z])(\d*)", part)
        assert m is not None, part
        f = space[m.group(1)]
        if f.kind == "categoric":
            cat += f"{m.group(1)}[{f.levels[int(m.group(2)) - 1]}]"
        else:
            num += m.group(1)
    return num + cat


def source(r_label: str) -> str:
    """Our ANOVA source of an R term label (``A:I(B^2)`` -> ``AB^2``)."""
    return "".join(re.sub(r"I\(([A-Z])\^2\)", r"\1^2", p) for p in r_label.split(":"))
