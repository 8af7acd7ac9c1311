"""Plots of lubricating-film results: pressure/film profiles, film maps, friction against μU."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Callable, Mapping, Sequence
    from types import ModuleType

    from matplotlib.figure import Figure

from .common import pyplot

__all__ = ["plot_ball_film", "plot_film_profiles", "plot_friction_vs_speed", "plot_oring",
           "plot_oring_cycle",
           "plot_reynolds_cylinder", "plot_slider", "plot_squeeze", "plot_stribeck"]


def _save(plt: ModuleType, fig: Figure, path: str | Path) -> None:
    fig.tight_layout()
    fig.savefig(Path(path), dpi=120)
    plt.close(fig)


def plot_film_profiles(steps: Sequence[Mapping[str, Any]] | None, path: str | Path, title: str,
                       variants: Mapping[str, Mapping[str, Any]] | None = None) -> None:
    """p(x) and h(x) per load step (colour), optionally per variant (line style).

    ``steps``: list of {"W", "x", "p", "h"} of one model; ``variants``: instead a
    dict {name: {"label", "steps"}} drawn on the same axes (the chapter's Figs. 22–23).
    """
    from matplotlib.lines import Line2D

    plt = pyplot()
    styles = ("-", "--", ":", "-.")
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5) if variants is None else (7, 7),
                                 sharex=True)
    groups = variants.values() if variants is not None else [{"label": None, "steps": steps}]
    handles = []
    for j, var in enumerate(groups):
        ls = styles[j % len(styles)]
        n = len(var["steps"])
        for k, st in enumerate(var["steps"]):
            c = plt.cm.viridis(k / max(1, n - 1))
            lab = f"W = {st['W']:.3g} N/mm" if j == 0 else None
            a1.plot(st["x"], st["p"], color=c, ls=ls, lw=1, label=lab)
            a2.plot(st["x"], 1e3 * np.asarray(st["h"]), color=c, ls=ls, lw=1)
        if var["label"] is not None:
            handles.append(Line2D([], [], color="k", ls=ls, lw=1, label=var["label"]))
    a1.set_ylabel("pressure p (MPa)")
    a1.legend(fontsize=7, ncol=2)
    a1.grid(alpha=0.3)
    a1.set_title(title)
    if handles:
        a2.legend(handles=handles, fontsize=7)
    a2.set_ylabel("film thickness h (µm)")
    a2.set_yscale("log")
    a2.set_xlabel("x (mm, cylinder frame)")
    a2.grid(alpha=0.3)
    _save(plt, fig, path)


def plot_friction_vs_speed(curves: Mapping[str | None, tuple[Sequence[float], Sequence[float]]],
                           path: str | Path) -> None:
    """Friction coefficient against μU (N/m), one curve per {label: (mu_U, friction)}."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5, 4))
    styles = ("-", "--", "-.", ":")
    for j, (label, (muU, f)) in enumerate(curves.items()):
        order = np.argsort(muU)
        ax.loglog(1e3 * np.asarray(muU)[order], np.asarray(f)[order],
                  "os^v"[j // 2 % 4] + styles[j % 4], label=label)
    ax.set_xlabel("μU (N/m)")
    ax.set_ylabel("friction coefficient")
    if len(curves) > 1 or next(iter(curves)) is not None:
        ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    _save(plt, fig, path)


def plot_ball_film(variants: Mapping[str, Mapping[str, Any]], W: float,
                   outdir: str | Path) -> None:
    """Ball-on-plane film: ``film_map.png`` and ``centerline.png`` in ``outdir``.

    The map shows h over the (x, y) projection of the first variant (mirrored in
    y), the centre line p and h on y = 0 of every variant.
    """
    import matplotlib.tri as mtri

    plt = pyplot()
    outdir = Path(outdir)
    var = next(iter(variants.values()))
    xy = np.asarray(var["xy"])
    x, y = np.r_[xy[:, 0], xy[:, 0]], np.r_[xy[:, 1], -xy[:, 1]]
    h = 1e3 * np.r_[var["h"], var["h"]]
    fig, ax = plt.subplots(figsize=(6, 5))
    cs = ax.tricontourf(mtri.Triangulation(x, y), np.minimum(h, 4 * float(np.min(h))),
                        levels=30, cmap="viridis")
    fig.colorbar(cs, ax=ax, label="film thickness h (µm, clipped)")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm, inlet on the left)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"{var['label']}: W = {W:g} N")
    _save(plt, fig, outdir / "film_map.png")

    styles = ("-", "--", "-.")
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True)
    for j, var in enumerate(variants.values()):
        a1.plot(var["x_axis"], var["p_axis"], ls=styles[j % 3], label=var["label"])
        a2.plot(var["x_axis"], 1e3 * np.asarray(var["h_axis"]), ls=styles[j % 3])
    a1.set_ylabel("pressure p (MPa)")
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3)
    a1.set_title(f"symmetry line y = 0, W = {W:g} N")
    a2.set_ylabel("film thickness h (µm)")
    a2.set_yscale("log")
    a2.set_xlabel("x (mm)")
    a2.grid(alpha=0.3)
    _save(plt, fig, outdir / "centerline.png")


def plot_slider(profile: Mapping[str, Any], path: str | Path) -> None:
    """Slider pressure against the analytic solution, and the film thickness."""
    from ..references import slider_reference

    plt = pyplot()
    pr = profile
    ref = slider_reference(pr["K"], pr["L"], pr["h0"], pr["U"], pr["mu"])
    xf = np.linspace(0, pr["L"], 400)
    fig, (ax, axh) = plt.subplots(2, 1, figsize=(6, 5.5), sharex=True,
                                  gridspec_kw={"height_ratios": [3, 1]})
    ax.plot(xf, ref["pressure"](xf), "k-", label="analytic")
    step = max(1, len(pr["x"]) // 60)
    ax.plot(pr["x"][::step], pr["p"][::step], "o", ms=3, label="tribofx (nodal)")
    ax.set_ylabel("pressure p (MPa)")
    ax.legend()
    ax.grid(alpha=0.3)
    axh.plot(pr["x"], 1e3 * pr["h"], "C1-")
    axh.set_ylabel("h (µm)")
    axh.set_xlabel("x (mm)")
    axh.grid(alpha=0.3)
    _save(plt, fig, path)


def plot_reynolds_cylinder(profile: Mapping[str, Any], path: str | Path) -> None:
    """Rigid cylinder: pressure vs half-Sommerfeld / Swift–Stieber, film, void fraction."""
    plt = pyplot()
    pr = profile
    jfo = "lam" in pr
    n = 3 if jfo else 2
    fig, axes = plt.subplots(n, 1, figsize=(6.5, 2.2 + 2.0 * n), sharex=True,
                             gridspec_kw={"height_ratios": [3] + [1] * (n - 1)})
    ax = axes[0]
    hs, ss = pr["refs"]["half_sommerfeld"], pr["refs"]["swift_stieber"]
    ax.plot(hs["x"], hs["p"], "k--", lw=1, label="half-Sommerfeld")
    ax.plot(ss["x"], ss["p"], "k-", lw=1, label="Swift–Stieber")
    ax.plot(pr["x"], pr["p"], "C0.-", ms=2, lw=0.8,
            label=f"tribofx (cavitation={pr['cavitation']})")
    ax.axvline(ss["x_rupture"], color="0.6", lw=0.5)
    ax.set_ylabel("pressure p (MPa)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    axes[1].plot(pr["x"], 1e3 * pr["h"], "C1-")
    axes[1].set_ylabel("h (µm)")
    axes[1].set_yscale("log")
    axes[1].grid(alpha=0.3)
    if jfo:
        axes[2].plot(pr["x"], pr["lam"], "C2.-", ms=2, lw=0.8)
        axes[2].set_ylabel("void fraction λ")
        axes[2].grid(alpha=0.3)
    axes[-1].set_xlabel("x (mm)")
    _save(plt, fig, path)


def _oring_axes(plt: ModuleType,
                groups: Mapping[str, tuple[Callable[[Mapping[str, Any]], str],
                                           Sequence[Mapping[str, Any]]]],
                title: str) -> Figure:
    """Plot p and h against z of the states of ``groups`` ({line style: [state]})."""
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6.5), sharex=True)
    h_scale = 1e-3
    for ls, (label, states) in groups.items():
        for k, st in enumerate(states):
            c = plt.cm.viridis(k / max(1, len(states) - 1))
            a1.plot(st["z"], st["p"], ls=ls, color=c, lw=1, marker="." if ls == ":" else None,
                    ms=2, label=label(st))
            a2.plot(st["z"], 1e3 * np.asarray(st["h"]), ls=ls, color=c, lw=1)
            h_scale = max(h_scale, st["h"][int(np.argmax(st["p"]))])
    a1.set_ylabel("film pressure p (MPa)")
    a1.legend(fontsize=7)
    a1.grid(alpha=0.3)
    a1.set_title(title)
    a2.set_ylabel("film thickness h (µm)")
    a2.set_ylim(0, 4e3 * h_scale)
    a2.set_xlabel("z (mm, position on the rod; air side > 0)")
    a2.grid(alpha=0.3)
    return fig


def plot_oring_cycle(hist: Mapping[str, Sequence[float]], outdir: str | Path) -> None:
    """O-ring over a reciprocating stroke: ``cycle.png``, rod speed, h_min, friction, air flux.

    ``hist``: the per-step lists of :mod:`tribofx.cases.ehl_oring` (time in s).
    """
    plt = pyplot()
    t = 1e3 * np.asarray(hist["time"])
    rows = (("rod_speed", 1.0, "rod speed (mm/s)"), ("h_min", 1e3, "h_min (µm)"),
            ("friction_force", 1.0, "film force, axial (N)"),
            ("flux_air", 1.0, "flux to air (mm³/s)"))
    fig, axes = plt.subplots(len(rows), 1, figsize=(6.4, 8.0), sharex=True)
    for ax, (key, scale, label) in zip(axes, rows):
        ax.plot(t, scale * np.asarray(hist[key]), ".-", ms=3)
        ax.set_ylabel(label)
        ax.axhline(0.0, color="0.7", lw=0.8)
    axes[-1].set_xlabel("time (ms)")
    axes[0].set_title("O-ring over a reciprocating stroke")
    _save(plt, fig, Path(outdir) / "cycle.png")


def plot_oring(profile: Mapping[str, Any], outdir: str | Path) -> None:
    """O-ring film: ``profiles.png`` (Fig. 17, outstroke solid, instroke dashed, per p_s).

    ``profile``: {"U": |U|, "strokes": {"out"/"in": [{"p_s", "z", "h", "p"}]}, "mesh":
    None or [{"mesh", "z", "h", "p"}]}; with a mesh study also ``mesh_study.png``
    (Figs. 18–19).
    """
    plt = pyplot()
    groups = {ls: (lambda st, tag=tag: f"{tag}stroke, p_s = {st['p_s']:g} MPa",
                   profile["strokes"].get(tag, [])) for tag, ls in (("out", "-"), ("in", "--"))}
    fig = _oring_axes(plt, groups, f"O-ring seal, |U| = {profile['U']:g} mm/s")
    _save(plt, fig, Path(outdir) / "profiles.png")
    if profile.get("mesh"):
        fig = _oring_axes(plt, {":": (lambda st: f"density {st['mesh']}", profile["mesh"])},
                          "mesh-density study (outstroke)")
        _save(plt, fig, Path(outdir) / "mesh_study.png")


def plot_squeeze(profile: Mapping[str, Any], outdir: str | Path) -> None:
    """Plot ``squeeze.png`` and ``squeeze_profiles.png`` of ``ehl-squeeze``.

    The first: film at the centre, minimum film and force against time, with the
    rigid references; the second: the final p and h against the radius.
    """
    plt = pyplot()
    t = 1e3 * np.asarray(profile["time"])
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    a1.plot(t, 1e3 * np.asarray(profile["h_center"]), "o-", ms=3, label="h at the centre")
    a1.plot(t, 1e3 * np.asarray(profile["h_min"]), "s--", ms=3, label="h_min")
    a1.plot(t, 1e3 * np.asarray(profile["h_center_rigid"]), "k:", label="rigid body")
    a1.set_ylabel("film (µm)")
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3)
    a2.plot(t, profile["force"], "o-", ms=3, label="film force")
    a2.plot(t, profile["force_rigid"], "k:", label="rigid body (speed) / load")
    a2.set_ylabel("force (N; N/mm in 2D)")
    a2.set_xlabel("time (ms)")
    a2.legend(fontsize=8)
    a2.grid(alpha=0.3)
    _save(plt, fig, Path(outdir) / "squeeze.png")
    X = np.asarray(profile["X"])
    r = np.linalg.norm(X[:, :-1] if X.shape[1] == 2 else X[:, :2], axis=1)
    order = np.argsort(r)
    fig, (b1, b2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    b1.plot(r[order], np.asarray(profile["p"])[order], ".", ms=3)
    b1.set_ylabel("pressure p (MPa)")
    b1.grid(alpha=0.3)
    b2.plot(r[order], 1e3 * np.asarray(profile["h"])[order], ".", ms=3)
    b2.set_ylabel("film h (µm)")
    b2.set_yscale("log")
    b2.set_xlabel("radius of the reference point (mm)")
    p = np.asarray(profile["p"])[order]
    loaded = r[order][p > 0.01 * p.max(initial=0.0)]
    if len(loaded):
        b2.set_xlim(0, 2 * loaded.max())
    b2.grid(alpha=0.3)
    _save(plt, fig, Path(outdir) / "squeeze_profiles.png")


def plot_stribeck(rows: Sequence[Mapping[str, float]], path: str | Path,
                  body: str = "cylinder") -> None:
    """Friction coefficient and film load fraction against speed (log), λ = h_c/σ on top."""
    plt = pyplot()
    U = [r["U"] for r in rows]
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(6.5, 6), sharex=True)
    a1.loglog(U, [r["friction_coefficient"] for r in rows], "o-", color="C3")
    a1.set_ylabel("friction coefficient")
    a1.grid(alpha=0.3, which="both")
    a1.set_title(f"Stribeck curve: soft {body} on a rough plane")
    for r in rows:
        a1.annotate(f"λ={r['lambda_ratio']:.2g}", (r["U"], r["friction_coefficient"]),
                    fontsize=7, textcoords="offset points", xytext=(3, 4))
    a2.semilogx(U, [r["film_load_fraction"] for r in rows], "s-", color="C0")
    a2.set_ylabel("film load / W")
    a2.set_xlabel("sliding speed U (mm/s)")
    a2.set_ylim(-0.05, 1.05)
    a2.grid(alpha=0.3, which="both")
    _save(plt, fig, path)


def plot_running_in(profile: Mapping[str, Any], path: str | Path) -> None:
    """Worn profiles (depth against x) and the load share and friction against time."""
    plt = pyplot()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    cmap = plt.get_cmap("viridis")
    times = profile["times"]
    X0 = np.asarray(profile["profiles"][0])
    for i, (t, X) in enumerate(zip(times, profile["profiles"])):
        X = np.asarray(X)
        a1.plot(X[:, 0], 1e3 * (X[:, 1] - X0[:, 1]), color=cmap(i / max(len(times) - 1, 1)),
                label=f"t = {t:.0f} s" if i in (0, len(times) - 1) else None)
    a1.set_xlabel("x (mm)")
    a1.set_ylabel("worn surface − initial surface (µm)")
    a1.set_title("worn profile of the cylinder")
    a1.grid(alpha=0.3)
    a1.legend(fontsize=8)
    t = profile["time"]
    a2.plot(t, profile["film_load_fraction"], "s-", color="C0", label="film load / W")
    a2.plot(t, np.asarray(profile["friction_coefficient"]) * 10, "o-", color="C3",
            label="10 × friction coefficient")
    a2.set_xlabel("time (s)")
    a2.set_ylim(bottom=0)
    a2.grid(alpha=0.3)
    a2.legend(fontsize=8)
    a2.set_title("running-in: the film builds up as the surface conforms")
    _save(plt, fig, path)
