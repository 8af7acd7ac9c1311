"""Plots of the wear groove of a ball sliding on a half-space (chapter §5.3, Figs. 9–10)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    import numpy.typing as npt

from .common import pyplot

__all__ = ["plot_groove", "plot_pressure_across"]


def _both_halves(p: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Mirror a half profile (y ≥ 0) to both halves of the groove."""
    p = np.asarray(p)
    return np.vstack([p[::-1] * [-1, 1], p[1:]])


def plot_groove(profile: Mapping[str, Any], outdir: str | Path,
                compare: Mapping[str, Any] | None = None) -> None:
    """``groove_profiles.png``, ``pressure_maps.png``, ``pressure_across.png``.

    ``profile``: the case's record (times, worn top-line profiles (y, z) in mm,
    nominal pressure maps (x, y, p) in mm and MPa, contact extents);
    ``compare``: a second profile (e.g. the graded layer) overlaid on the
    pressure-across plot (Fig. 10 bottom, homogeneous vs graded).
    """
    plt = pyplot()
    outdir = Path(outdir)
    fig, ax = plt.subplots(figsize=(6, 3.5))
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(profile["times"])))
    for t, pts, c in zip(profile["times"], profile["profiles"], colors):
        p = _both_halves(pts)
        ax.plot(p[:, 0], 1e3 * p[:, 1], lw=1, color=c, label=f"t = {t:g} s")
    ymax = 1.5 * max(profile["contact_radius"])
    ax.set_xlim(-ymax, ymax)
    ax.set_xlabel("y (mm)")
    ax.set_ylabel("worn surface z (µm)")
    ax.set_title(f"wear groove, {profile['scheme']} scheme")
    if len(profile["times"]) <= 12:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(outdir / "groove_profiles.png", dpi=120)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    lim = 1.5 * max(max(profile["contact_radius"]), max(profile["contact_half_length"]))
    for ax, i in zip(axes, (0, -1)):
        m = np.asarray(profile["maps"][i])
        m = np.vstack([m, m * [1, -1, 1]])
        sel = (np.abs(m[:, 0]) < lim) & (np.abs(m[:, 1]) < lim)
        sc = ax.tricontourf(m[sel, 0], m[sel, 1], m[sel, 2], levels=20, cmap="viridis")
        fig.colorbar(sc, ax=ax, label="p (MPa)")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm, sliding)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"contact pressure, t = {profile['times'][i]:g} s")
    fig.tight_layout()
    fig.savefig(outdir / "pressure_maps.png", dpi=120)
    plt.close(fig)

    entries = [("graded" if prof["graded"] else "homogeneous", prof["pressure_x0"],
                prof["pressure_integral"]) for prof in (profile, compare) if prof is not None]
    plot_pressure_across(entries, outdir / "pressure_across.png", profile["times"][-1], ymax)


def plot_pressure_across(entries: Sequence[tuple[str, Sequence[tuple[float, float]],
                                                 Sequence[tuple[float, float]]]],
                         path: str | Path, t: float, ymax: float) -> None:
    """Pressure across the groove at x = 0 and ∫ p dx versus y (Fig. 10 bottom).

    ``entries``: list of (label, [(y, p)], [(y, ∫p dx)]) in mm, MPa and N/mm, e.g.
    homogeneous and graded; ``t`` the time (s), ``ymax`` the plotted half-width (mm).
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.5))
    for (label, px0, pint), style in zip(entries, ("-o", "--s", ":^")):
        p = np.asarray(px0)
        axes[0].plot(p[:, 0], p[:, 1], style, ms=3, label=label)
        q = np.asarray(pint)
        axes[1].plot(q[:, 0], q[:, 1], style, ms=3, label=label)
    axes[0].set_ylabel("p at x = 0 (MPa)")
    axes[1].set_ylabel("∫ p dx (N/mm)")
    for ax in axes:
        ax.set_xlabel("y (mm)")
        ax.set_xlim(0, ymax)
        ax.legend(fontsize=8)
    fig.suptitle(f"pressure across the groove at t = {t:g} s (Fig. 10 bottom)")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
