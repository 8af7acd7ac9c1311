"""Plots of the two-body wear case: the configurations of Fig. 5 and the wear histories."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Mapping

    import numpy.typing as npt
    from matplotlib.axes import Axes

from .common import pyplot

__all__ = ["plot_reciprocating"]

_COLUMNS = ("start of the run-in (−A)", "start of the cycle (centre)", "right-most (+A)")


def _draw(ax: Axes, cells: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64],
                                 npt.NDArray[np.float64]], color: str) -> None:
    """Worn undeformed mesh (grey fill) and deformed mesh (edges) of one body."""
    from matplotlib.collections import PolyCollection

    X, w, u = cells
    # matplotlib's stub wants a Sequence of polygons; an (n, k, 2) array is one
    ax.add_collection(PolyCollection(X + w,  # type: ignore[arg-type]
                                     facecolor="0.88", edgecolor="none"))
    ax.add_collection(PolyCollection(X + w + u,  # type: ignore[arg-type]
                                     facecolor="none", edgecolor=color, lw=0.25))


def plot_reciprocating(profile: Mapping[str, Any], outdir: str | Path) -> None:
    """``fig5.png``: initial and worn, undeformed and deformed; ``wear.png``: histories."""
    plt = pyplot()
    outdir = Path(outdir)
    shots = profile.get("shots", {})
    rows = [k for k in ("initial", "worn") if k in shots]
    if rows:
        fig, axes = plt.subplots(len(rows), 3, figsize=(11, 2.6 * len(rows)), squeeze=False)
        for i, key in enumerate(rows):
            for j, (pin, block) in enumerate(shots[key]):
                ax = axes[i, j]
                _draw(ax, block, "tab:blue")
                _draw(ax, pin, "tab:red")
                ax.set_xlim(*profile["view"][0])
                ax.set_ylim(*profile["view"][1])
                ax.set_aspect("equal")
                ax.set_xticks([])
                ax.set_yticks([])
                ax.set_title(f"{key}: {_COLUMNS[j]}", fontsize=8)
        fig.suptitle("grey: undeformed (worn) configuration; lines: deformed (pin red, "
                     "block blue)", fontsize=8)
        fig.tight_layout()
        fig.savefig(outdir / "fig5.png", dpi=90)
        plt.close(fig)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.6))
    c = np.asarray(profile["cycles_done"], float)
    a1.plot(c, profile["worn_area_pin"], "o-", label="pin")
    a1.plot(c, profile["worn_area_block"], "s-", label="block")
    a1.set_xlabel("cycles")
    a1.set_ylabel("worn area (mm²/mm)")
    a1.legend()
    for key, label in (("wear_pin", "pin"), ("wear_block", "block")):
        if key in profile:
            d = profile[key]
            a2.plot(d["X_hat"][:, 0], d["depth"], ".-", label=label)
    a2.set_xlabel("initial position X̂ (mm)")
    a2.set_ylabel("final wear depth (mm)")
    a2.legend()
    fig.tight_layout()
    fig.savefig(outdir / "wear.png", dpi=120)
    plt.close(fig)
