"""The model's tests, folded as the package is (build, contract, engines, readings, choice, faces,
pipelines; cross-cutting checks of ``fit`` here). This folder holds the published references
(``_published``), the R names (``_r_names``) and the exact arithmetic (``_exact``) that the
subfolders' tests import: pytest puts this folder on the import path with this file."""
