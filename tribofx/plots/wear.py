"""Plots of the wear cases: worn profiles, wear histories, error versus Δt, scar growth."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..references import rigid_cap_radius
from ..scheme import Scheme
from .common import pyplot

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    import numpy.typing as npt
    from matplotlib.axes import Axes

__all__ = ["error_curve", "plot_dt_study", "plot_wear_ball", "plot_wear_pin"]


def plot_wear_pin(profile: Mapping[str, Any], outdir: str | Path) -> None:
    """Worn profiles at every step (``profiles.png``) and wear history (``wear.png``)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(6, 3.5))
    for t, pts in zip(profile["times"], profile["profiles"]):
        p = np.asarray(pts)
        ax.plot(p[:, 0], p[:, 1], lw=1, label=f"t = {t:g} s")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"worn tip, {profile['scheme']} scheme, Δt = {profile['dt']:g} s")
    if len(profile["times"]) <= 12:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(Path(outdir) / "profiles.png", dpi=120)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.plot(profile["time"], profile["wear_volume"], "o-", label="worn area (mm²/mm)")
    ax.plot(profile["time"], profile["max_wear_depth"], "s-", label="max depth (mm)")
    ax.set_xlabel("t (s)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(Path(outdir) / "wear.png", dpi=120)
    plt.close(fig)


def error_curve(ax: Axes, dts: npt.ArrayLike, errors: Sequence[float | None],
                unstable: Sequence[bool], color: str, label: str,
                dt_cr: float | None = None) -> None:
    """One error-versus-Δt curve (log-log) of a Fig. 4 panel.

    ``errors``: per Δt, None for a failed run; ``unstable``: per Δt, drawn as red
    crosses (at the largest error where the run failed); ``dt_cr`` dotted.
    """
    dts = np.asarray(dts, dtype=float)
    err = np.array([np.nan if e is None else e for e in errors])
    bad = np.asarray(unstable, dtype=bool)
    ax.loglog(dts, err, "o-", color=color, label=label)
    if bad.any():
        top = np.nanmax(err) if np.isfinite(err).any() else 1.0
        ax.loglog(dts[bad], np.where(np.isfinite(err[bad]), err[bad], top), "x",
                  color="red", ms=10, mew=2)
    if dt_cr:
        ax.axvline(dt_cr, color=color, ls=":", lw=1)


def plot_dt_study(study: Mapping[str, Any], outdir: str | Path) -> None:
    """Plot ``study=dt``: ``error_vs_dt.png`` and ``profiles.png``.

    ``error_vs_dt.png``: log-log, a panel per scheme (explicit, implicit, bdf2), one curve per
    mesh, unstable runs as red crosses, Δt_cr dotted (like Fig. 4).
    ``profiles.png``: worn profiles every 200 s (the largest Δt) for Δt = 200 s
    and 5 s (or the largest and smallest Δt) against the reference, explicit
    left, implicit right, one row per mesh (like Fig. 3).
    """
    plt = pyplot()
    dts = np.asarray(study["dts"])
    schemes = study.get("schemes", ["explicit", "implicit"])
    fig, axes = plt.subplots(1, len(schemes), figsize=(5 * len(schemes), 4), sharey=True,
                             squeeze=False)
    for ax, scheme in zip(axes[0], schemes):
        for i, (key, m) in enumerate(study["meshes"].items()):
            error_curve(ax, dts, m[f"error_{scheme}"], m[f"unstable_{scheme}"], f"C{i}",
                        f"{key}, {scheme}", m["dt_cr"] if scheme == "explicit" else None)
        ok = [e for m in study["meshes"].values() for e in m[f"error_{scheme}"] if e]
        if ok:  # slope guide: 1, or 2 for BDF2
            x, q = np.array([dts.min(), dts.max()]), 2 if Scheme.of(scheme).bdf2 else 1
            ax.loglog(x, min(ok) * (x / dts.min()) ** q, "k--", lw=0.8, label=f"slope {q}")
        ax.set_xlabel("Δt (s)")
        ax.set_title(f"{scheme}, E = {study['E']:g} MPa (× unstable, ⋮ Δt_cr)")
        ax.legend(fontsize=7)
    axes[0, 0].set_ylabel("error of the worn contact profile (mm)")
    fig.suptitle(f"reference: {study['reference']}", fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(outdir) / "error_vs_dt.png", dpi=120)
    plt.close(fig)

    big, small = max(dts), min(dts)
    if 5.0 in dts:
        small = 5.0
    if 200.0 in dts:
        big = 200.0
    meshes = study["meshes"]
    fig, axes = plt.subplots(len(meshes), 2, figsize=(10, 3.2 * len(meshes)), squeeze=False)
    for row, (key, m) in zip(axes, meshes.items()):
        ref = m["runs"]["reference"]["profiles"]
        marks = [t for t in ref["times"] if abs(t / big - round(t / big)) < 1e-9]
        ylim = None
        for ax, scheme in zip(row, ("explicit", "implicit")):
            for dt, style in ((big, "-"), (small, "--")):
                run = m["runs"].get((scheme, dt))
                if run is None or run["profiles"] is None:
                    continue
                for j, (t, p) in enumerate(zip(run["profiles"]["times"],
                                               run["profiles"]["profiles"])):
                    if any(abs(t - s) < 1e-6 for s in marks):
                        p = np.asarray(p)
                        ax.plot(p[:, 0], p[:, 1], style, color="C0" if dt == big else "C1",
                                lw=1, label=f"Δt = {dt:g} s" if j == 0 else None)
            for j, (t, p) in enumerate(zip(ref["times"], ref["profiles"])):
                if t in marks:
                    p = np.asarray(p)
                    ax.plot(p[:, 0], p[:, 1], ":", color="k", lw=1,
                            label=f"reference Δt = {m['runs']['reference']['dt']:g} s"
                            if j == 0 else None)
                    lo, hi = p[:, 1].min(), p[:, 1].max()
                    ylim = (min(lo, ylim[0]) if ylim else lo, max(hi, ylim[1]) if ylim else hi)
            if ylim:
                pad = 0.3 * (ylim[1] - ylim[0])
                ax.set_ylim(ylim[0] - pad, ylim[1] + pad)
            ax.set_title(f"{scheme}, {key}, E = {study['E']:g} MPa, t = {marks[0]:g}…"
                         f"{marks[-1]:g} s", fontsize=9)
            ax.set_xlabel("X (mm)")
            ax.set_ylabel("worn Y (mm)")
            ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(Path(outdir) / "profiles.png", dpi=120)
    plt.close(fig)


def plot_wear_ball(profile: Mapping[str, Any], outdir: str | Path) -> None:
    """Plot ``pressure.png``, ``profiles.png`` and ``scar.png`` of ``wear-ball-flat``.

    Initial/final pressure on the contact plane, worn profile along y = 0 at
    every step, scar radius against the rigid-cap law.
    """
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, title in zip(axes, ("initial_plane", "final_plane"),
                              ("t = 0", f"t = {profile['time'][-1]:g} s")):
        pts = np.asarray(profile[key])
        if len(pts) >= 3:
            # mirror the half model about y = 0
            x = np.concatenate([pts[:, 0], pts[:, 0]])
            y = np.concatenate([pts[:, 1], -pts[:, 1]])
            p = np.concatenate([pts[:, 2], pts[:, 2]])
            sc = ax.tricontourf(x, y, p, levels=20, cmap="viridis")
            fig.colorbar(sc, ax=ax, label="contact pressure (MPa)")
            ax.plot(pts[:, 0], pts[:, 1], "k.", ms=2)
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm, sliding direction)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"contact pressure, {title}")
    fig.tight_layout()
    fig.savefig(Path(outdir) / "pressure.png", dpi=120)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(7, 3.5))
    for t, pts in profile["profiles"]:
        p = np.asarray(pts)
        ax.plot(p[:, 0], p[:, 1] * 1e3, lw=1, label=f"t = {t:g} s")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("worn z (µm)")
    ax.set_title(f"worn ball profile on y = 0, {profile['scheme']} scheme")
    if len(profile["profiles"]) <= 14:
        ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    fig.savefig(Path(outdir) / "profiles.png", dpi=120)
    plt.close(fig)

    t = np.asarray(profile["time"])[1:]
    s = profile["V"] * t
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(s, np.asarray(profile["contact_radius"])[1:], "o", label="contact radius")
    ax.loglog(s, np.asarray(profile["scar_radius"])[1:], "s", label="flat-scar radius")
    ax.loglog(s, rigid_cap_radius(profile["k"], profile["F"], profile["R"], s), "k-",
              label="(4kFRs/π)^{1/4}")
    ax.set_xlabel("sliding distance s (mm)")
    ax.set_ylabel("radius (mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(Path(outdir) / "scar.png", dpi=120)
    plt.close(fig)
