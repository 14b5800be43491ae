"""The page of an ``rsm-lrg loop`` study: the best setting found with its Gaussian-process
prediction interval, the convergence curve (best so far per evaluation) and the model's
leave-one-out check, as one self-contained HTML page (no script; the curve is a PNG
``data:`` URI)."""

from __future__ import annotations

from typing import Any

__all__ = ["loop_html"]


def _curve_figure(summary: dict) -> Any:
    from matplotlib.figure import Figure

    curve = summary["convergence"]
    x = [c["evaluation"] for c in curve]
    fig = Figure(figsize=(5.6, 3.4))
    ax = fig.add_subplot(1, 1, 1)
    ax.plot(x, [c["value"] for c in curve], "o", color="0.6", markersize=3.5, label="run")
    ax.step(x, [c["best_so_far"] for c in curve], where="post", color="C0", linewidth=1.8, label="best so far")
    first = [c["evaluation"] for c in curve if c["round"] > 0]
    if first:
        ax.axvline(first[0] - 0.5, color="0.3", linestyle=":", linewidth=1.0)
    ax.set_xlabel("evaluation")
    ax.set_ylabel(str(summary["response"]).replace("$", r"\$"))
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    return fig


def loop_html(summary: dict, factors: list[str], notes: list[str] | None = None, *, title: str | None = None) -> str:
    """The page of a study summary (the dictionary :func:`rsm_lrg.cli.loop_study.run_study`
    returns and ``study.json`` records): every user text escaped by the template."""
    from .html import fmt_num, render_page
    from .plots import to_data_uri

    best = summary["best"]
    goal = f"target {fmt_num(summary['target'])}" if summary["goal"] == "target" else summary["goal"]
    stop = {"budget": "the budget was spent",
            "ei-tol": "the largest expected improvement fell below --ei-tol times the range of the responses"}
    facts = [("Response", f"{summary['response']} ({goal})"),
             ("Evaluations", f"{summary['evaluations']} of a budget of {summary['budget']}, in {summary['rounds']} "
                             f"round(s)"),
             ("Stopped because", stop.get(str(summary["stopped_because"]), str(summary["stopped_because"]))),
             ("Best run", f"evaluation {best['evaluation']} (round {best['round']}): "
                          f"{summary['response']} = {fmt_num(best['observed'])}"),
             ("GP prediction there", f"{fmt_num(best['predicted'])}, 95% prediction interval "
                                     f"[{fmt_num(best['pi_low'])}, {fmt_num(best['pi_high'])}]"),
             ("Leave-one-out check", f"Q² = {summary['loo']['q2']:.4f}, RMSE = {fmt_num(summary['loo']['rmse'])}")]
    setting = [(name, fmt_num(best["setting"][name])) for name in factors]
    rows = [(c["evaluation"], c["round"], fmt_num(c["value"]), fmt_num(c["best_so_far"]))
            for c in summary["convergence"]]
    return render_page("loop.html.j2", title=title or f"Closed loop: {summary['response']}",
                       subtitle="Gaussian process and expected improvement (rsm-lrg loop)",
                       toc=[("summary", "Summary"), ("best", "Best setting"), ("convergence", "Convergence"),
                            ("notes", "Notes")],
                       facts=facts, setting=setting, curve_uri=to_data_uri(_curve_figure(summary)), rows=rows,
                       notes=list(notes or ()))
