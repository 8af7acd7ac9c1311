"""Plots of contact results: the Hertz pressure profile."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Mapping

from .common import pyplot

__all__ = ["plot_hertz_pressure"]


def plot_hertz_pressure(profile: Mapping[str, Any], path: str | Path) -> None:
    """Nodal contact pressure against the Hertz distribution p₀√(1 − r²/a²)."""
    plt = pyplot()
    a, p0 = profile["a"], profile["p0"]
    r = np.linspace(0, a, 200)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(r, p0 * np.sqrt(1 - (r / a) ** 2), "k-", label="Hertz")
    mask = profile["r"] < 1.6 * a
    ax.plot(profile["r"][mask], profile["p"][mask], "o", ms=3, label="tribofx (nodal)")
    ax.set_xlabel("x (mm)" if profile["dim"] == 2 else "r (mm)")
    ax.set_ylabel("contact pressure (MPa)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(Path(path), dpi=120)
    plt.close(fig)
