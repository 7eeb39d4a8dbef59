"""``compare(a, b, plot=...)``: the overlay of two runs' tendon forces, A solid and B dashed, as
PNG and SVG beside each other, with the same colours, title and axes as ``compare --plot``.
Drawn with matplotlib (the ``plot`` extra), so that the extension carries no plotting code."""

from __future__ import annotations

import os
from pathlib import Path

#: The first four colours of the command line's plots (matplotlib's tab10), by muscle.
COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd")


def overlay(a: "Run", b: "Run", out: str | os.PathLike[str]) -> None:  # noqa: F821
    """Writes ``out`` with the suffixes ``.png`` and ``.svg``."""
    try:
        import matplotlib

        matplotlib.use("Agg", force=False)
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("compare(plot=...) needs matplotlib: pip install matplotlib") from e
    fig = Figure(figsize=(8, 5), dpi=100)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    for i, name in enumerate(a.muscles):
        color = COLORS[i % len(COLORS)]
        for run, style in ((a, "-"), (b, "--")):
            if name in run.muscles:
                j = run.muscles.index(name)
                ax.plot(run.time, run["force"][:, j], style, color=color, label=f"{name} ({run.model})")
    ax.set_title(f"Tendon force: {a.model} (solid) vs {b.model} (dashed)")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("force (N)")
    ax.grid(alpha=0.3)
    ax.legend(loc="best", fontsize="small")
    fig.tight_layout()
    out = Path(out)
    for suffix in (".png", ".svg"):
        fig.savefig(out.with_suffix(suffix))
