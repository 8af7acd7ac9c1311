"""Hertz contact: an elastic cylinder (plane strain) or sphere pressed on a rigid plane.

The body is symmetry-reduced (half cylinder cross-section x ≥ 0 / quarter
sphere x, y ≥ 0), clamped on its flat face, and the rigid plane is pushed
against it.  The plane position δ is found by a secant iteration so that the
normal contact force equals the prescribed ``load``; the load is applied in
``steps`` increments (friction makes the response path dependent).

Hertz reference: :func:`tribofx.references.hertz_reference` (E* = E/(1 − ν²)
against a rigid plane; 2D: load per unit length, half-width; 3D: radius).

Your own body (``mesh_file``): a gmsh ``.msh`` of dimension ``dim`` with the
physical groups ``contact``, ``loaded`` (the flat face, clamped),
``symmetry_x`` and, in 3D, ``symmetry_y``, read and checked by
:func:`tribofx.meshes.user.read_user_mesh` and placed by
:func:`tribofx.cases.curved_bodies.read_hertz_body`.  The Hertz comparison stays
against R, E, ν and the load, so the mesh must be the symmetry-reduced cylinder (the x ≥ 0 half of
its cross-section) or sphere (the x, y ≥ 0 quarter) of radius R whose lowest
point touches the plane: it is moved so that its symmetry planes are x = 0
(and y = 0) and its lowest contact node is on the plane y = 0 (2D) / z = 0
(3D), and rejected (one-line error) if a symmetry group is not a plane, the
body is not on the positive side of it, or the curvature of ``contact`` at the
first-contact point is not 1/R to within 5 % (a forgotten ``R``).  ``mesh`` is
then ignored; the augmentation ρ_N = E/h takes h from the user's contact
facets near the first-contact point (see :func:`tribofx.cases.curved_bodies.read_hertz_body`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..interfaces import Contact
from ..meshes.hertz import NAMES, hertz_body
from ..obstacles import rigid_plane, rigid_surface_mesh
from ..params import CaseParams, InputError, param
from ..problem import NewtonDivergence, Problem
from ..references import hertz_reference

# hertz_reference is re-exported from tribofx.references
from .curved_bodies import (
    AXISYMMETRIC,
    CURVATURE_TOL,
    body_kind,
    dimension,
    geometric_dim,
    hertz_dim,
    read_hertz_body,
)

if TYPE_CHECKING:
    from collections.abc import Mapping
    from pathlib import Path

    from dolfinx import fem
    from tqdm import tqdm

    from ..obstacles import AnalyticObstacle, MeshedObstacle
    from ..output import RunRecord

__all__ = ["AXISYMMETRIC", "Model", "Params", "build", "dimension", "doc", "geometric_dim",
           "hertz_dim", "hertz_reference", "mesh_sizes", "model_fraction", "name", "plot",
           "progress_total", "resumable", "run", "validate", "vtx_fields"]


name = "hertz"
resumable = False   # no per-step checkpoint
doc = ("elastic cylinder (dim=2) or sphere (dim=3: quarter model, dim=axisymmetric: "
       "meridian section) pressed on a rigid plane, vs Hertz")


@dataclass(frozen=True)
class Params(CaseParams):
    """The parameters of ``hertz`` (``--set KEY=VALUE``)."""

    dim: int | str = param(
        2, "-",
        "2: plane-strain cylinder, 3: sphere (quarter model), "
        "axisymmetric: sphere (meridian section x >= 0, the axis x = 0)",
        choices=(2, 3, AXISYMMETRIC), parse=dimension)
    E: float = param(10.0, "MPa", "Young's modulus", lower=0.0)
    nu: float = param(0.3, "-", "Poisson's ratio (compressible law)", lower=-1.0, upper=0.5)
    R: float = param(10.0, "mm", "radius of the cylinder/sphere", lower=0.0)
    load: float | None = param(
        None, "N/mm (dim=2) or N (dim=3, axisymmetric)",
        "total normal load on the full body (default 0.2 N/mm in 2D, 0.5 N in 3D)",
        lower=0.0)
    friction: float = param(0.0, "-", "Coulomb friction coefficient", lower=0.0, closed=True)
    obstacle: str = param(
        "analytic", "-",
        "rigid plane in closed form or as a gmsh mesh",
        choices=("analytic", "mesh"))
    material: str = param("neo-hookean", "-", "strain energy", choices=("neo-hookean", "linear"))
    mesh: int = param(
        2, "-",
        "refinement level: contact-zone element size a/(6·2^mesh) in 2D, a/(2·2^mesh) "
        "in 3D, a = Hertz contact size (ignored with mesh_file)",
        lower=0, upper=7, closed=True)
    steps: int = param(2, "-", "load increments", lower=1, upper=1000, closed=True)
    mesh_file: str = param(
        "", "-",
        "your own body: a gmsh .msh of dimension dim, the x >= 0 half cylinder or "
        "x, y >= 0 quarter sphere of radius R with physical groups contact, loaded, "
        "symmetry_x (and symmetry_y in 3D), moved onto the plane; replaces mesh "
        "(see the case's description)")

    def __post_init__(self) -> None:
        if self.load is None:   # the default: 0.2 N/mm (dim=2), 0.5 N (dim=3, axisymmetric)
            object.__setattr__(self, "load", 0.2 if self.dim == 2 else 0.5)
        super().__post_init__()


def validate(v: Params) -> None:
    """Check cross-parameter consistency."""
    assert v.load is not None   # its default filled by Params.__post_init__
    a, _ = hertz_reference(hertz_dim(v.dim), v.E, v.nu, v.R, v.load)
    if a > 0.5 * v.R:
        raise InputError(f"load too large for a Hertz comparison: a/R = {a / v.R:.2f} > 0.5")
    if a < 1e-4 * v.R:
        raise InputError(f"load too small to resolve: a/R = {a / v.R:.1e} < 1e-4")


def mesh_sizes(v: Params) -> tuple[float, float, float]:
    """Element sizes (fine, coarse) and radius of the refined zone, all in mm."""
    assert v.load is not None   # its default filled by Params.__post_init__
    a, _ = hertz_reference(hertz_dim(v.dim), v.E, v.nu, v.R, v.load)
    plane = geometric_dim(v.dim) == 2       # a 2D mesh: cylinder or meridian section
    per_a = (6 if plane else 2) * 2 ** v.mesh
    return a / per_a, v.R / (6 if plane else 4), 1.5 * a


class Model(NamedTuple):
    """What :func:`build` assembles: the body, its contact with the plane, the problem."""

    body: Body
    contact: Contact
    problem: Problem


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """Body, contact interface and :class:`Problem` of the case (not yet loaded).

    ``mesh_file``: the user's body
    (:func:`tribofx.cases.curved_bodies.read_hertz_body`); ρ_N = E/h with h its
    contact element size instead of ``h_fine``.
    """
    R, dim = v.R, geometric_dim(v.dim)
    h_fine, h_coarse, r_fine = mesh_sizes(v)
    assert v.load is not None   # its default filled by Params.__post_init__
    if v.mesh_file:
        a, _ = hertz_reference(hertz_dim(v.dim), v.E, v.nu, R, v.load)
        msh, ft, names, h_fine, _ = read_hertz_body(v.mesh_file, comm, dim, a, R,
                                                    CURVATURE_TOL / R)
    else:
        msh, ft = hertz_body(dim, R, h_fine, h_coarse, r_fine, comm)
        names = NAMES
    normal = np.eye(dim)[dim - 1]
    if v.obstacle == "analytic":
        plane = rigid_plane(np.zeros(dim), normal)
    else:
        from ..meshes.obstacles import plane_surface_mesh

        plane = rigid_surface_mesh(*plane_surface_mesh(dim, (-0.2 * R, 1.2 * R),
                                                       4 * h_fine))
    mu, lmbda = lame_parameters(v.E, v.nu)
    kind = body_kind(v.dim)
    body = Body(msh, ft, names, kind,
                (v.material, {"mu": mu, "lmbda": lmbda}))
    body.add_dirichlet("loaded", np.zeros(dim))
    body.add_dirichlet("symmetry_x", 0.0, component=0)
    if dim == 3:
        body.add_dirichlet("symmetry_y", 0.0, component=1)
    contact = Contact(body, "contact", plane, rho_n=v.E / h_fine,
                      friction=v.friction)
    return Model(body, contact, Problem([body, contact], name="hertz"))


def vtx_fields(model: Model) -> dict[str, list[fem.Function]]:
    """Fields written for ParaView: displacement (bulk) and nominal pressure (Γ_c)."""
    return {"displacement": [model.body.u], "contact": [model.contact.lam_n]}


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """Pressure profile against Hertz (``pressure.png``)."""
    from ..plots import plot_hertz_pressure

    plot_hertz_pressure(profile, outdir / "pressure.png")


def model_fraction(dim: int | str) -> float:
    """Fraction of the full body whose force the model gives (symmetry).

    A half cylinder, a quarter sphere; the meridian section's forces are those
    of the revolved (full) sphere, its measures weighted by 2πR.
    """
    return {2: 0.5, 3: 0.25, AXISYMMETRIC: 1.0}[dim]


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: the load steps."""
    return v.steps


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        comm: MPI.Comm = MPI.COMM_WORLD) -> Model:
    """Load the body to ``load`` and record contact size and peak pressure.

    The plane's position δ is driven by :meth:`Continuation.reach` so that the
    normal contact force equals each load increment.  ``comm``: the
    communicator of the mesh (e.g. COMM_SELF for a serial run inside a parallel
    test).
    """
    R, dim = v.R, hertz_dim(v.dim)
    assert v.load is not None   # its default filled by Params.__post_init__
    model = build(v, comm)
    contact, problem = model.contact, model.problem
    frac = model_fraction(v.dim)
    record.data["num_dofs"] = problem.num_dofs
    a_h, p_h = hertz_reference(dim, v.E, v.nu, R, v.load)
    axis = geometric_dim(v.dim) - 1
    plane = cast("AnalyticObstacle | MeshedObstacle", contact.counterpart)  # a rigid plane
    control = Continuation(problem, ConstantParameter(plane.offset, axis),
                           response=lambda: contact.force()[axis], verbose=verbose,
                           record=record.data["newton_iterations"])
    targets = [frac * v.load * (k + 1) / v.steps for k in range(v.steps)]
    delta = a_h**2 / R if dim == 3 else 0.5 * a_h**2 / R
    try:
        for k, target in enumerate(targets):
            delta = control.reach(target, delta * (1 if k == 0 else (k + 1) / k))
            if progress is not None:
                progress.update(1)
    except NewtonDivergence as err:
        err.model = model  # restored to the last converged load step
        raise
    finally:
        _report(contact, v, record, frac, a_h, p_h)
    return model


def _report(contact: Contact, v: Params, record: RunRecord, frac: float, a_h: float,
            p_h: float) -> None:
    dim, gdim = v.dim, geometric_dim(v.dim)
    area, pmax = contact.measures()
    # half-width; the radius of a quarter disc's area; that of the revolved disc's
    size = {2: area, 3: math.sqrt(4 * area / math.pi),
            AXISYMMETRIC: math.sqrt(area / math.pi)}[dim]
    force = contact.force()
    key = "contact_half_width" if dim == 2 else "contact_radius"
    record.result(key, size, "mm")
    record.result(f"hertz_{key}", a_h, "mm")
    record.result("p_max", pmax, "MPa")
    record.result("hertz_p_max", p_h, "MPa")
    record.result(f"{key}_rel_error", size / a_h - 1)
    record.result("p_max_rel_error", pmax / p_h - 1)
    record.result("contact_element_size", v.E / contact.rho_n, "mm (h of rho_N = E/h)")
    if hertz_dim(dim) == 3:   # a sphere: the plane's travel from first contact
        plane = cast("AnalyticObstacle | MeshedObstacle", contact.counterpart)
        delta = abs(float(plane.offset.value[gdim - 1]))
        record.result("approach", delta, "mm")
        record.result("hertz_approach", a_h**2 / v.R, "mm (half-space)")
    record.result("normal_load_full_body", float(force[gdim - 1] / frac),
                  "N/mm" if dim == 2 else "N")
    record.result("tangential_force_modelled_part", [float(f) for f in force[: gdim - 1]],
                  "N/mm" if dim == 2 else "N")
    # weighted L2 distance of the nodal pressures from the Hertz distribution
    d = contact.nodal_data()
    rr = d["x"][:, 0] if gdim == 2 else np.linalg.norm(d["x"][:, :2], axis=1)
    ph = p_h * np.sqrt(np.clip(1 - (rr / a_h) ** 2, 0, None))
    comm = contact.body.mesh.comm
    num = comm.allreduce(float(np.sum(d["weight"] * (d["p"] - ph) ** 2)), op=MPI.SUM)
    den = comm.allreduce(float(np.sum(d["weight"] * ph**2)), op=MPI.SUM)
    record.result("pressure_profile_rel_l2_error", math.sqrt(num / den))
    prof = contact.gather_profile()
    if comm.rank == 0:
        assert prof is not None     # gathered on rank 0
        r = (prof["x"][:, 0] if gdim == 2
             else np.linalg.norm(prof["x"][:, :2], axis=1))
        record.profile = {"r": r, "p": prof["p"], "a": a_h, "p0": p_h, "dim": dim}
