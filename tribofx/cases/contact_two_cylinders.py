"""Two elastic cylinders pressed together (plane strain), against Hertz.

Two deformable bodies (chapter §2): the upper cylinder (radius R1, centre
(0, R1)) is the slave, the lower one (radius R2, centre (0, −R2)) the master —
or, with ``R2=0``, a flat elastic block [0, 2R1] × [−2R1, 0].  Both are
symmetry-reduced (x ≥ 0), refined around the initial contact point (the
origin) and carry finite-strain neo-Hookean laws with their own E and ν.  The
slave's flat face is held, the master's flat (or bottom) face is pushed up by
δ; :class:`~tribofx.continuation.Continuation` finds δ for each load
increment from the contact force.  The contact is
:class:`~tribofx.interfaces.TwoBodyContact` (the C++ closest-point kernel on
the current master surface, exact tangent in slave and master dofs).

Reference (:func:`tribofx.references.hertz`, line contact): 1/R* = 1/R1 +
1/R2, 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2, a = (4PR*/(πE*))^½,
p0 = 2P/(πa); P the load per unit length of the full cylinders.

Your own bodies: ``mesh_file`` (the upper cylinder, body 1) and ``mesh_file2``
(the lower body, body 2), each a 2D gmsh ``.msh`` of the x ≥ 0 half of its
body with the physical groups the case gives its own meshes — ``contact``,
``loaded`` (the flat face: held on the upper body, pushed up on the lower one)
and ``symmetry_x`` (x = 0) — one file per body, as the two bodies are two
meshes here; either may be given alone (the other body is built).  The Hertz
reference stays the one of R1, R2, E1, E2, ν1, ν2 and the load, so each mesh
must be its body: it is moved (:func:`tribofx.cases.curved_bodies.read_hertz_body`)
so that symmetry_x is x = 0 and its first-contact point (the lowest contact
node of the upper body, the highest of the lower one) is at the origin, and
rejected if its curvature there is not 1/R1 (1/R2; 0 for R2 = 0, a flat)
within 5 % of 1/R*.  ``mesh`` then refines only a body that is built; ρ_N =
min(E1, E2)/h with h the smaller contact element size of the two bodies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..interfaces import TwoBodyContact
from ..meshes.hertz import NAMES, hertz_body
from ..params import CaseParams, InputError, param
from ..problem import NewtonDivergence, Problem
from ..references import hertz
from .curved_bodies import CURVATURE_TOL, read_hertz_body

if TYPE_CHECKING:
    from collections.abc import Mapping
    from pathlib import Path

    from tqdm import tqdm

    from ..output import RunRecord
    from ..references import HertzContact

__all__ = ["Model", "Params", "build", "doc", "name", "plot", "progress_total", "reference",
           "report", "resumable", "run", "validate", "vtx_fields"]


name = "contact-two-cylinders"
resumable = False   # no per-step checkpoint
doc = "two elastic plane-strain cylinders (or a cylinder on a block) pressed together"


@dataclass(frozen=True)
class Params(CaseParams):
    """The parameters of ``contact-two-cylinders`` (``--set KEY=VALUE``)."""

    R1: float = param(10.0, "mm", "radius of the upper (slave) cylinder", lower=0)
    R2: float = param(
        10.0, "mm",
        "radius of the lower (master) cylinder; 0: flat block",
        lower=0, closed=True)
    E1: float = param(10.0, "MPa", "Young's modulus of the upper cylinder", lower=0)
    E2: float = param(10.0, "MPa", "Young's modulus of the lower body", lower=0)
    nu1: float = param(0.3, "-", "Poisson's ratio of the upper cylinder", lower=-1, upper=0.5)
    nu2: float = param(0.3, "-", "Poisson's ratio of the lower body", lower=-1, upper=0.5)
    load: float = param(0.2, "N/mm", "normal load per unit length (full cylinders)", lower=0)
    friction: float = param(0.0, "-", "Coulomb friction coefficient", lower=0, closed=True)
    mesh: int = param(
        1, "-",
        "refinement: contact-zone elements a/(6·2^mesh) (of the "
        "bodies not given by mesh_file, mesh_file2)",
        lower=0, upper=6, closed=True)
    steps: int = param(2, "-", "load increments", lower=1, upper=100, closed=True)
    mesh_file: str = param(
        "", "-",
        "your own upper (slave) cylinder: a 2D gmsh .msh of its x >= 0 half, radius R1, "
        "with physical groups contact, loaded (flat top face, held) and symmetry_x "
        "(x = 0); moved so that symmetry_x is x = 0 and its lowest contact point is at "
        "the origin; tip curvature 1/R1 within 5 % of 1/R*; replaces mesh for it")
    mesh_file2: str = param(
        "", "-",
        "your own lower (master) body: as mesh_file, radius R2 (R2 = 0: a flat block), "
        "loaded = its bottom face (pushed up), its highest contact point moved to the "
        "origin; tip curvature 1/R2 (0 for R2 = 0) within 5 % of 1/R*")


def reference(v: Params) -> HertzContact:
    """Hertz line contact of the two bodies (a flat for R2 = 0)."""
    R2 = math.inf if v.R2 == 0 else v.R2
    return hertz(v.load, v.R1, v.E1, v.nu1, R2, v.E2, v.nu2, line=True)


def validate(v: Params) -> None:
    """Reject loads with a/R* > 0.3 (no Hertz comparison) or a/R* < 1e-4."""
    h = reference(v)
    if h.a > 0.3 * h.R_star:
        raise InputError(f"load too large for a Hertz comparison: a/R* = "
                         f"{h.a / h.R_star:.2f} > 0.3")
    if h.a < 1e-4 * h.R_star:
        raise InputError(f"load too small to resolve: a/R* = {h.a / h.R_star:.1e}")


@dataclass
class Model:
    """What :func:`build` assembles: the two cylinders, their contact, the problem.

    ``push``: the Dirichlet value of the lower cylinder's loaded face (its lift).
    """

    upper: Body
    lower: Body
    contact: TwoBodyContact
    problem: Problem
    push: fem.Constant


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """Upper body, lower body, contact and problem (unloaded).

    A body given by ``mesh_file`` (upper) or ``mesh_file2`` (lower) is read
    and placed by :func:`tribofx.cases.curved_bodies.read_hertz_body`; ρ_N = E_min/h
    with h the smaller contact element size of the two bodies.
    """
    h = reference(v)
    h_fine = h.a / (6 * 2 ** v.mesh)
    bodies: list[Body] = []
    sizes: list[float] = []
    for k, (R, E, nu) in enumerate(((v.R1, v.E1, v.nu1),
                                    (v.R2, v.E2, v.nu2))):
        path = (v.mesh_file, v.mesh_file2)[k]
        if path:
            msh, ft, names, h_k, _ = read_hertz_body(
                path, comm, 2, h.a, R, CURVATURE_TOL / h.R_star, name=f"R{k + 1}",
                below=k == 1)
        else:
            size = R if R > 0 else 2 * v.R1
            msh, ft = hertz_body(2, size, h_fine, size / 6, 1.5 * h.a, comm, below=k == 1,
                                 block=size if R == 0 else None)
            names, h_k = NAMES, h_fine
        sizes.append(h_k)
        mu, lmbda = lame_parameters(E, nu)
        body = Body(msh, ft, names, "plane_strain",
                    ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
                    name=("upper", "lower")[k])
        body.add_dirichlet("symmetry_x", 0.0, component=0)
        bodies.append(body)
    upper, lower = bodies
    upper.add_dirichlet("loaded", np.zeros(2))
    push = lower.add_dirichlet("loaded", 0.0, component=1)
    E_min = min(v.E1, v.E2)
    contact = TwoBodyContact(upper, "contact", lower, "contact", rho_n=E_min / min(sizes),
                             friction=v.friction)
    problem = Problem([upper, lower, contact], name="two_cylinders")
    return Model(upper, lower, contact, problem, push)


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the load steps."""
    return v.steps


def run(v: Params, record: RunRecord, progress: tqdm | None = None,
        verbose: bool = False) -> Model:
    """Press the bodies to ``load`` in ``steps``; record a, p_max and Hertz."""
    run = build(v)
    contact, problem = run.contact, run.problem
    record.data["num_dofs"] = problem.num_dofs
    h = reference(v)
    control = Continuation(problem, ConstantParameter(run.push),
                           response=lambda: contact.forces(problem)[0][1],
                           verbose=verbose, record=record.data["newton_iterations"])
    delta = 0.25 * h.a**2 / h.R_star
    try:
        for k in range(v.steps):
            target = 0.5 * v.load * (k + 1) / v.steps   # half model
            delta = control.reach(target, delta * (1 if k == 0 else (k + 1) / k))
            if progress is not None:
                progress.update(1)
    except NewtonDivergence as err:
        err.model = run
        raise
    finally:
        report(run, v, record, h)
    return run


def report(run: Model, v: Params, record: RunRecord, h: HertzContact) -> None:
    """Contact half-width (sum of active lumped current lengths) and peak pressure."""
    contact, problem = run.contact, run.problem
    d = contact.nodal_data(problem)
    comm = contact.slave.mesh.comm
    a = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
    p_max = comm.allreduce(float(np.max(d["p"], initial=0.0)), op=MPI.MAX)
    on_upper, _ = contact.forces(problem)
    record.result("contact_half_width", a, "mm")
    record.result("hertz_contact_half_width", h.a, "mm")
    record.result("p_max", p_max, "MPa")
    record.result("hertz_p_max", h.p0, "MPa")
    record.result("contact_half_width_rel_error", a / h.a - 1)
    record.result("p_max_rel_error", p_max / h.p0 - 1)
    record.result("contact_element_size", min(v.E1, v.E2) / contact.rho_n,
                  "mm (h of rho_N = min(E1, E2)/h)")
    record.result("normal_load_full_body", 2 * float(on_upper[1]), "N/mm")
    # equilibrium of the solved upper cylinder: its held face balances the contact
    upper = run.upper
    record.result("equilibrium_error",
                  abs(upper.reaction("loaded", 1) + float(on_upper[1])), "N/mm")
    record.result("equilibrium_bound", upper.V.dofmap.index_map.size_global * 2
                  * upper.tolerances()[upper.u].atol, "N/mm")
    prof = contact.gather_profile(problem)
    if comm.rank == 0:
        assert prof is not None     # gathered on rank 0
        record.profile = {"r": prof["x"][:, 0], "p": prof["p"], "a": h.a, "p0": h.p0,
                          "dim": 2}


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacements of both bodies (one file per mesh)."""
    return {"upper": [run.upper.u], "lower": [run.lower.u]}


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """Pressure profile against Hertz (``pressure.png``)."""
    from ..plots import plot_hertz_pressure

    plot_hertz_pressure(profile, outdir / "pressure.png")
