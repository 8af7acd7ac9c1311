"""The plane inclined slider: the Reynolds equation in 1D between rigid surfaces.

On an interval mesh (the planar, traditional form §6.6 of the chapter, with the
weak forms of ``forms/reynolds.py``; the 1D film of
:func:`tribofx.cases.film_setup.rigid_film`, shared with ``reynolds-cylinder``).

``reynolds-slider`` — plane inclined slider (pad at rest, plane runner sliding
at U, so v̄ = U/2 and ∂h/∂t = 0 by eq. 61), gap h = h0(1 + K − K x/L) on
0 ≤ x ≤ L, p = 0 at both ends; compared with the closed-form pressure, load and
peak of :func:`tribofx.references.slider_reference` (Reynolds 1886, Cameron).

``reynolds-cylinder``: :mod:`tribofx.cases.reynolds_cylinder`.

Units: mm, N, s, MPa (viscosity MPa·s; loads per unit width/length N/mm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
import ufl
from mpi4py import MPI

from ..params import InputError, param
from ..positions import parabolic_vertex
from ..problem import NewtonDivergence
from ..references import (
    barus_pressure,
    slider_pressure,
    slider_reference,
)
from .film_setup import FluidParams, density, rigid_film, viscosity

if TYPE_CHECKING:
    from pathlib import Path

    from dolfinx import fem
    from tqdm import tqdm

    from ..output import RunRecord
    from .film_setup import FilmModel

# slider_reference is re-exported from tribofx.references
__all__ = ["Params", "build", "doc", "name", "plot", "progress_total", "resumable", "run",
           "slider_reference", "validate", "vtx_fields"]


# --------------------------------------------------------------------------- slider case


name = "reynolds-slider"
resumable = False   # no per-step checkpoint
doc = "rigid plane inclined slider bearing (1D Reynolds), vs the analytic solution"


@dataclass(frozen=True)
class Params(FluidParams):
    """The parameters of ``reynolds-slider`` (``--set KEY=VALUE``)."""

    K: float = param(1.0, "-", "inclination: inlet gap h0(1+K) over outlet gap h0", lower=-1.0)
    L: float = param(10.0, "mm", "slider length", lower=0.0)
    h0: float = param(0.01, "mm", "outlet (minimum) film thickness", lower=0.0)
    U: float = param(1000.0, "mm/s", "speed of the sliding plane (pad at rest)", lower=0.0)
    mu: float = param(1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s oil)", lower=0.0)
    mesh: int = param(200, "-", "number of elements", lower=2, upper=10**7, closed=True)
    degree: int = param(1, "-", "Lagrange degree of the pressure", choices=(1, 2))


def validate(v: Params) -> None:
    """Barus: α p_iso,max < 1 (the reference transform; the fluid stays finite)."""
    viscosity(v)
    density(v)
    if v.viscosity == "barus":
        ap = v.alpha_p * slider_reference(v.K, v.L, v.h0, v.U, v.mu)["p_max"]
        if not ap < 0.95:
            raise InputError(f"alpha·p_max of the isoviscous slider = {ap:.3g}: the Barus "
                             f"pressure −ln(1 − αp)/α needs < 1 (0.95 here); lower alpha_p")


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> FilmModel:
    """Return the film of the slider and its problem (not solved)."""
    K, L, h0 = v.K, v.L, v.h0
    return rigid_film(comm, 0.0, L, v.mesh, v.degree,
                      lambda x: h0 * (1 + K - K * x / L), 0.5 * v.U, viscosity(v),
                      h_ref=h0, density=density(v))


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the one solve."""
    return 1


def run(v: Params, record: RunRecord, progress: tqdm | None = None,
        verbose: bool = False) -> FilmModel:
    """Solve, then record load, peak pressure and the L2 error against the analytic p."""
    run = film, problem = build(v)
    record.data["num_dofs"] = problem.num_dofs
    try:
        report = problem.solve_by_homotopy(verbose=verbose)
    except NewtonDivergence as err:
        err.model = run
        raise
    record.data["newton_iterations"].append([report.iterations])
    record.data["newton_residuals"] = [float(r) for r in report.residuals]
    if progress is not None:
        progress.update(1)
    K, L, h0, U, mu = v.K, v.L, v.h0, v.U, v.mu
    ref = dict(slider_reference(K, L, h0, U, mu))
    load = film.integral(film.p)
    p_ex = slider_pressure(ufl.SpatialCoordinate(film.sub)[0], K, L, h0, U, mu)
    if v.density != "incompressible":    # no closed form
        ref = {"load": math.nan, "p_max": math.nan, "x_p_max": math.nan}
    elif v.viscosity == "barus":   # the exact transform of the isoviscous film
        a = v.alpha_p
        p_ex = barus_pressure(p_ex, a, ufl.ln)
        ref["p_max"] = barus_pressure(ref["p_max"], a)   # monotone: the same x_p_max
        ref["load"] = film.integral(p_ex)
    elif v.viscosity != "constant":
        ref = {"load": math.nan, "p_max": math.nan, "x_p_max": math.nan}
    l2 = math.sqrt(film.integral((film.p - p_ex) ** 2))
    nrm = math.sqrt(film.integral(p_ex**2))
    prof = film.profile()
    peak = None
    if film.sub.comm.rank == 0:
        assert prof is not None   # rank 0 holds the gathered profile
        i = int(np.argmax(np.abs(prof["p"])))
        peak = (float(prof["p"][i]), parabolic_vertex(prof["x"], np.abs(prof["p"])))
        record.profile = {"x": prof["x"], "p": prof["p"], "h": prof["h"], "K": K, "L": L,
                          "h0": h0, "U": U, "mu": mu}
    pm, xm = film.sub.comm.bcast(peak, root=0)
    record.result("load_per_width", load, "N/mm")
    record.result("analytic_load_per_width", ref["load"], "N/mm")
    record.result("p_max", pm, "MPa")
    record.result("analytic_p_max", ref["p_max"], "MPa")
    record.result("x_p_max", xm, "mm")
    record.result("analytic_x_p_max", ref["x_p_max"], "mm")

    def rel(a: float, b: float) -> float | None:
        return a / b - 1 if b != 0 else None

    record.result("load_rel_error", rel(load, ref["load"]))
    record.result("p_max_rel_error", rel(pm, ref["p_max"]))
    record.result("pressure_l2_error", l2, "MPa·mm^0.5")
    record.result("pressure_rel_l2_error", l2 / nrm if nrm > 0 else None)
    return run


def vtx_fields(run: FilmModel) -> dict[str, list[fem.Function]]:
    """Pressure and film thickness on the interval mesh."""
    return {"reynolds": [run.film.p, run.film.h_fun]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """Pressure against the analytic solution and film thickness (``pressure.png``)."""
    from ..plots import plot_slider

    plot_slider(profile, outdir / "pressure.png")
