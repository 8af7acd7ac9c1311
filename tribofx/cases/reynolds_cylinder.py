"""Hydrodynamic lubrication of a rigid cylinder near a plane: the Reynolds equation in 1D.

``reynolds-cylinder`` — rigid cylinder of radius R near a rigid plane, parabolic
gap h = h0 + x²/(2R) on x_in ≤ x ≤ x_out, mean entrainment speed u_m (both
surfaces rolling/sliding so that v̄ = u_m), p = 0 at the inlet.  Cavitation
models: ``none`` (full Sommerfeld, p = 0 also at x_out; the reported load is the
positive part, the half-Sommerfeld/Gümbel convention), ``penalty`` (p ≥ 0 by a
penalty; this is the variational-inequality solution, whose rupture satisfies
the Swift–Stieber conditions p = p' = 0), ``jfo`` (mass-conserving JFO model,
unknowns p and λ; inlet p = 0, λ = 0 (flooded), outlet natural: no Poiseuille
flux, and p = 0 there by complementarity since the outlet lies in the
cavitation zone).  References, computed by NumPy quadrature independently of
the FE code for the same inlet position: the half-Sommerfeld and the
Swift–Stieber solutions of :func:`tribofx.references.cylinder_references`.

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
from ..references import cylinder_references
from .film_setup import FluidParams, density, rigid_film, viscosity

if TYPE_CHECKING:
    from collections.abc import Mapping
    from pathlib import Path

    import numpy.typing as npt
    from dolfinx import fem
    from tqdm import tqdm

    from ..interfaces import RigidFilm
    from ..output import RunRecord
    from .film_setup import FilmModel

# cylinder_references is re-exported from tribofx.references
__all__ = ["Params", "build", "cylinder_references", "doc", "mesh_levels", "name", "plot",
           "progress_total", "resumable", "run", "scales", "validate", "vtx_fields"]


def _peak_and_rupture(prof: Mapping[str, npt.NDArray[np.float64]], crossing: bool
                      ) -> tuple[float, float, float]:
    """Peak (nodal p_max, sub-element x_p_max) and rupture point downstream of the peak.

    ``crossing``: linear zero crossing of p (no cavitation model).  Otherwise a
    sub-element estimate: at a Swift–Stieber rupture p = p' = 0, so p ≈ c (x_r − x)²
    and √p is linear in x near x_r.  A straight line is fitted to √p at the three
    positive nodes before the last positive one and extrapolated to zero; the last
    positive node is left out because its element straddles the free boundary,
    where the discrete law (nodal complementarity or penalty) is not the smooth
    double root.  With fewer positive nodes: the first cavitated node.
    """
    x, p = prof["x"], prof["p"]
    i = int(np.argmax(p))
    pm, xm = float(p[i]), parabolic_vertex(x, p)
    if crossing:
        neg = np.nonzero(p[i:] < 0)[0]
        if not len(neg):
            return pm, xm, float(x[-1])
        j = i + neg[0]
        return pm, xm, float(x[j - 1] - p[j - 1] * (x[j] - x[j - 1]) / (p[j] - p[j - 1]))
    zero = np.nonzero(p[i:] <= 1e-9 * pm)[0]
    if not len(zero):
        return pm, xm, float(x[-1])
    j = i + zero[0]                      # first node of the cavitated zone
    if j - i < 5:
        return pm, xm, float(x[j])
    k = slice(j - 4, j - 1)
    slope, icpt = np.polyfit(x[k], np.sqrt(p[k]), 1)
    if slope >= 0:                       # not decaying like a double root
        return pm, xm, float(x[j])
    return pm, xm, float(-icpt / slope)


def _reformation(prof: Mapping[str, npt.NDArray[np.float64]]) -> float | None:
    """JFO: first node from the inlet where the film is full (λ = 0); None without λ."""
    if "lam" not in prof:
        return None
    full = np.nonzero(prof["lam"] <= 1e-12)[0]
    return float(prof["x"][full[0]]) if len(full) else None


name = "reynolds-cylinder"
resumable = False   # no per-step checkpoint
doc = ("rigid cylinder on a rigid plane (1D Reynolds) with cavitation none|penalty|jfo, "
       "vs half-Sommerfeld and Swift–Stieber")


@dataclass(frozen=True)
class Params(FluidParams):
    """The parameters of ``reynolds-cylinder`` (``--set KEY=VALUE``)."""

    R: float = param(10.0, "mm", "cylinder radius", lower=0.0)
    h0: float = param(0.01, "mm", "minimum film thickness", lower=0.0)
    um: float = param(1000.0, "mm/s", "mean entrainment speed (u1 + u2)/2", lower=0.0)
    mu: float = param(1e-7, "MPa·s", "viscosity (1e-7 MPa·s = 0.1 Pa·s oil)", lower=0.0)
    x_in: float = param(-2.0, "mm", "inlet position (p = 0)", upper=0.0)
    x_out: float = param(2.0, "mm", "outlet position", lower=0.0)
    cavitation: str = param("penalty", "-", "cavitation model", choices=("none", "penalty", "jfo"))
    supg: bool = param(True, "-", "SUPG stabilisation (Remark 3.2)")
    mesh: int = param(400, "-", "number of elements", lower=2, upper=10**7, closed=True)
    degree: int = param(1, "-", "Lagrange degree of p (jfo: 1 only)", choices=(1, 2))
    inlet_void: float = param(
        0.0, "-",
        "void fraction λ of the supplied film at x_in (jfo; 0: fully flooded, "
        "> 0: starved inlet)",
        lower=0.0, upper=1.0, closed=True)
    inlet: str = param(
        "dirichlet", "-",
        "jfo inlet: dirichlet (λ = inlet_void, p = 0 "
        "at x_in) or supply (an open end supplied with the content (1 − inlet_void) "
        "h(x_in), as the reciprocating O-ring's air end)",
        choices=("dirichlet", "supply"))
    penalty: float = param(
        1e-6, "-",
        "relative penalty ε/ε_ref, ε_ref = 12 μ ℓ²/h0³ (MPa·s/mm), ℓ = √(2 R h0)",
        lower=0.0)


def scales(v: Params) -> tuple[float, float, float]:
    """Contact length ℓ = √(2Rh0) (mm), pressure scale 12μu_mℓ/h0² (MPa), ε (MPa·s/mm)."""
    ell = math.sqrt(2 * v.R * v.h0)
    p_s = 12 * v.mu * v.um * ell / v.h0 ** 2
    eps = v.penalty * 12 * v.mu * ell**2 / v.h0 ** 3
    return ell, p_s, eps


def validate(v: Params) -> None:
    """Check the interval and, with cavitation, that the outlet lies past the rupture."""
    if not v.x_in < v.x_out:
        raise InputError(f"x_in = {v.x_in} mm must be < x_out = {v.x_out} mm")
    viscosity(v)
    density(v, v.cavitation)
    if v.cavitation == "jfo" and v.degree != 1:
        raise InputError("cavitation=jfo needs degree=1 (nodal complementarity)")
    if v.inlet_void > 0 and v.cavitation != "jfo":
        raise InputError("inlet_void > 0 (starved inlet) needs cavitation=jfo")
    if max(-v.x_in, v.x_out) >= v.R:
        raise InputError(f"x_in, x_out must lie within the cylinder's radius R = {v.R} mm "
                         f"(the gap h0 + x²/(2R) is its parabolic approximation)")
    if v.cavitation != "none":
        try:
            refs = cylinder_references(v.R, v.h0, v.um, v.mu, v.x_in,
                                       v.x_out, n=20_000, inlet_void=v.inlet_void)
        except ValueError as err:
            raise InputError(str(err)) from None
        xr = refs["swift_stieber"]["x_rupture"]
        if v.x_out < xr + 0.02 * (v.x_out - v.x_in):
            raise InputError(f"x_out = {v.x_out} mm must lie downstream of the "
                             f"cavitation boundary (Swift–Stieber x_r = {xr:.4g} mm)")


def mesh_levels(n: int, coarsest: int = 50) -> list[int]:
    """Element counts of the nested iteration: n/2^k, ..., n/2, n with n/2^k ≥ coarsest.

    Each level starts from the solution of the previous one, so that the
    semismooth Newton iteration only moves the free boundaries by about one
    coarse element (a primal active-set iteration moves them by about one
    node per iteration).
    """
    out = [n]
    while out[0] // 2 >= coarsest:
        out.insert(0, out[0] // 2)
    return out


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> FilmModel:
    """Return the film of the cylinder gap and its problem (not solved; JFO guess set)."""
    R, h0 = v.R, v.h0
    _, p_s, eps = scales(v)
    return rigid_film(comm, v.x_in, v.x_out, v.mesh, v.degree,
                      lambda x: h0 + x**2 / (2 * R), v.um, viscosity(v),
                      cavitation=v.cavitation, supg=v.supg, p_c=p_s, eps=eps,
                      h_ref=h0, lam_in=v.inlet_void, density=density(v, v.cavitation),
                      supply=v.inlet == "supply")


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the nested solve, once."""
    return 1


def run(v: Params, record: RunRecord, progress: tqdm | None = None,
        verbose: bool = False) -> FilmModel:
    """Solve and record load, peak, rupture point and fluxes against the references."""
    levels = mesh_levels(v.mesh)
    its, prev, run = [], None, None
    try:
        for n in levels:  # nested iteration: each level from the coarser solution
            run = film, problem = build(v.replace(mesh=n))
            if prev is not None:
                film.set_from_profile(prev)
            report = problem.solve_by_homotopy(verbose=verbose)
            its.append(report.iterations)
            prev = film.sub.comm.bcast(film.profile(), root=0)
    except NewtonDivergence as err:
        err.model = run
        raise
    record.data["num_dofs"] = problem.num_dofs
    record.data["mesh_levels"] = levels
    record.data["newton_iterations"].append(its)
    record.data["newton_residuals"] = [float(r) for r in report.residuals]
    if progress is not None:
        progress.update(1)
    _report(film, v, record)
    assert run is not None   # mesh_levels gives at least one level
    return run


def _report(film: RigidFilm, v: Params, record: RunRecord) -> None:
    cav = v.cavitation
    ell, p_s, eps = scales(v)
    refs = cylinder_references(v.R, v.h0, v.um, v.mu, v.x_in, v.x_out,
                               inlet_void=v.inlet_void)
    p, comm = film.p, film.sub.comm
    load = film.integral(ufl.max_value(p, 0) if cav == "none" else p)
    q_in, q_out = film.consistent_fluxes(inlet=lambda y: np.isclose(y[0], v.x_in))
    prof = film.profile()
    peak: tuple[float | None, ...] | None = None
    if comm.rank == 0:
        assert prof is not None   # rank 0 holds the gathered profile
        peak = _peak_and_rupture(prof, crossing=(cav == "none"))
        peak = (*peak, _reformation(prof))
        record.profile = dict(prof, cavitation=cav, refs={
            k: {"x": r["x"][::50], "p": r["p"][::50], "x_rupture": r["x_rupture"]}
            for k, r in refs.items()})
    pm, xm, xr, xf = comm.bcast(peak, root=0)
    record.result("load_per_length", load, "N/mm")
    record.result("p_max", pm, "MPa")
    record.result("x_p_max", xm, "mm")
    record.result("x_rupture", xr, "mm")
    if cav == "jfo":
        record.result("x_reformation", xf, "mm")
        record.result("swift_stieber_x_reformation", refs["swift_stieber"]["x_reformation"],
                      "mm")
    for key, r in refs.items():
        record.result(f"{key}_load_per_length", float(r["load"]), "N/mm")
        record.result(f"{key}_p_max", float(r["p_max"]), "MPa")
        record.result(f"{key}_x_p_max", float(r["x_p_max"]), "mm")
        record.result(f"{key}_x_rupture", float(r["x_rupture"]), "mm")
        record.result(f"{key}_flux", float(r["flux"]), "mm^2/s")
    if v.viscosity == "constant" and v.density == "incompressible":
        ref = refs["half_sommerfeld" if cav == "none" else "swift_stieber"]
        record.result("reference", "half_sommerfeld" if cav == "none" else "swift_stieber")
        record.result("load_rel_error", float(load / ref["load"] - 1))
        record.result("p_max_rel_error", float(pm / ref["p_max"] - 1))
    else:   # the references above are those of the isoviscous, incompressible fluid
        record.result("reference", "none (the references are isoviscous, incompressible)")
    record.result("flux_in", float(q_in), "mm^2/s")
    record.result("flux_out", float(q_out), "mm^2/s")
    record.result("mass_balance_rel_defect", float((q_out - q_in) / abs(q_in)))
    record.result("pressure_scale", p_s, "MPa")
    if cav == "penalty":
        record.result("penalty_epsilon", eps, "MPa·s/mm")
        record.result("p_min", comm.allreduce(float(p.x.array.min(initial=0.0)),
                                              op=MPI.MIN), "MPa")


def vtx_fields(run: FilmModel) -> dict[str, list[fem.Function]]:
    """Pressure, film thickness (and void fraction for JFO) on the interval mesh."""
    film = run.film
    return {"reynolds": [film.p, film.h_fun] + ([film.lam] if film.lam is not None else [])}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """Pressure vs half-Sommerfeld / Swift–Stieber, film thickness, void fraction."""
    from ..plots import plot_reynolds_cylinder

    plot_reynolds_cylinder(profile, outdir / "pressure.png")
