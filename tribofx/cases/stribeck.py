"""The Stribeck curve of a soft cylinder or ball sliding on a rough rigid plane.

``stribeck`` — a neo-Hookean cylinder (``geometry=cylinder``: radius R, plane
strain, both sides of the contact modelled, W in N/mm) or ball (``geometry=ball``:
the quarter model of ``ehl-ball``, W in N on the whole ball) at rest on a rigid
plane that slides at U (mm/s) under it (:mod:`tribofx.cases.rough_contact`);
the film between them is the chapter's
:class:`~tribofx.interfaces.Film` with a :class:`~tribofx.roughness.Roughness`:
the average-flow Reynolds equation (Patir–Cheng flow factors) and the
Greenwood–Tripp asperity pressure p_a(h) with boundary friction μ_b p_a, the
roughness σ on the plane.  The film and the asperities share the load:
W = ∫ (p + p_a) — the film alone at high speed (λ = h_c/σ ≳ 3), the asperities
alone at low speed, mixed between.

The load is reached at the highest speed by the approach of the plane (a secant
on log W inside a load march), then the speed is marched down through
``speeds`` (geometric steps, cut on failure), W held by the approach at each.

Asperity data: σ (mm, combined RMS), ``eta_beta_sigma`` (ηβσ), ``sigma_beta`` (σ/β):
K = (16√2/15)π(ηβσ)²√(σ/β), E* = E/(1 − ν²); the defaults (0.1, 0.1) are a rough
counterface (machined metals, Greenwood & Williamson 1966: 0.03–0.05, 1e-4–1e-2).

Results per speed: ``friction_coefficient`` (the tangential force on the
body over W: fluid shear plus μ_b times the asperity load),
``film_load_fraction`` (film load / W), ``lambda_ratio`` (h_c/σ), ``h_central``,
``h_min``, ``p_max`` (film), ``p_total_max`` (film and asperities),
``newton_iterations``; ``stribeck.png``.  Units: mm, N, s, MPa.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from mpi4py import MPI

from ..params import InputError, number_list, param
from ..problem import NewtonDivergence
from .rough_contact import RoughContactParams, build, check, load_and_slow, measures

if TYPE_CHECKING:
    from pathlib import Path

    from dolfinx import fem
    from tqdm import tqdm

    from ..output import RunRecord
    from .rough_contact import Model

__all__ = ["Params", "doc", "name", "plot", "progress_total", "report", "resumable", "run",
           "validate", "vtx_fields"]


name = "stribeck"
resumable = False   # no per-step checkpoint
doc = "Stribeck curve of a soft cylinder or ball sliding on a rough rigid plane (mixed EHL)"


@dataclass(frozen=True)
class Params(RoughContactParams):
    """The parameters of ``stribeck`` (``--set KEY=VALUE``)."""

    geometry: str = param("cylinder", "-", "cylinder (plane strain) or ball (3D quarter)",
                          choices=("cylinder", "ball"))
    speeds: str = param("1000,300,100,30,10,3,1,0.3,0.1,0.03,0.01", "mm/s",
                        "sliding speeds, decreasing (comma-separated)")


def speeds(v: Params) -> list[float]:
    """Return the speeds (mm/s), decreasing (one-line error otherwise)."""
    U = number_list(v.speeds, "speeds")
    if any(u <= 0 for u in U) or any(b >= a for a, b in zip(U, U[1:])):
        raise InputError("speeds must be positive and decreasing")
    return U


def validate(v: Params) -> None:
    """Bad input: a one-line error."""
    check(v, v.geometry, speeds(v))


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: one per speed."""
    return len(speeds(v))


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        comm: MPI.Comm = MPI.COMM_WORLD, rough: bool = True) -> Model:
    """Reach W at the first speed, then march the speed down; record per speed.

    ``rough=False``: the smooth film (the chapter's) at the same speeds.
    """
    run = build(v, v.geometry, speeds(v)[0], comm, rough)
    assert run.problem is not None   # build (shape=False) builds it
    record.data["num_dofs"] = run.problem.num_dofs
    rows: list[dict[str, Any]] = []

    def on_speed(U: float, iterations: int) -> None:
        rows.append(dict(measures(run, v), U=U, newton_iterations=iterations))
        if progress is not None:
            progress.update(1)

    try:
        load_and_slow(run, v, speeds(v), verbose, on_speed)
    except NewtonDivergence as err:
        err.model = run
        raise
    finally:
        report(rows, record, v.geometry)
    return run


def report(rows: list[dict[str, Any]], record: RunRecord, geometry: str = "cylinder"
           ) -> None:
    """Per-speed lists and the curve for the plot."""
    units = {"U": "mm/s", "friction_coefficient": "-", "film_load_fraction": "-",
             "lambda_ratio": "-", "h_central": "mm", "h_min": "mm", "W": "N/mm | N",
             "p_max": "MPa", "p_total_max": "MPa",
             "newton_iterations": "-"}
    for key, unit in units.items():
        record.result(key if key != "U" else "speeds", [r[key] for r in rows], unit)
    if MPI.COMM_WORLD.rank == 0 and rows:
        record.profile = {"rows": rows, "geometry": geometry}


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacement of the cylinder."""
    return {"displacement": [run.body.u]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """``stribeck.png``: friction coefficient and film load fraction against speed."""
    from ..plots.film import plot_stribeck

    plot_stribeck(profile["rows"], outdir / "stribeck.png", profile.get("geometry", "cylinder"))
