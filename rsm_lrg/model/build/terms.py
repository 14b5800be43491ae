"""Model terms and the model matrix (moved to :mod:`rsm_lrg.terms`, below the designs and the
model, so that optimal designs build the same matrix as the fit); re-exported here."""

from ...terms import (  # noqa: F401
    MAX_TERMS,
    MIXTURE_ORDERS,
    MODELS,
    Term,
    __all__,  # noqa: F401
    block_contrasts,
    check_model_size,
    column_names,
    design_gradient,
    design_matrix,
    effect_codes,
    model_matrix,
    model_terms,
    n_columns,
    n_model_terms,
    parse_term,
    scheffe_names,
    term_columns,
    term_name,
)
