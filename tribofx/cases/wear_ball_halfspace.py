"""Rigid ball sliding against an elastic half-space: wear groove (chapter §5.3, Figs. 9–10).

Case ``wear-ball-halfspace``: a rigid ball (radius R, load F) slides at speed V over
an elastic half-space, in the Eulerian frame of the ball (§4.3, slip velocity from
v = F V, eqs. 26–27); frictionless contact, Archard wear Ẇ = k p ‖v_T‖ (eq. 14;
``law=spatial``: eqs. 15–16) averaged along the track of length L per cycle.  The
configuration: a :class:`tribofx.body.Body` (the 3D block; its shape field is an
image Function, so the graded modulus can depend on the worn depth), a
:class:`tribofx.interfaces.Contact` with a rigid sphere, a
:class:`tribofx.interfaces.steady_wear.SteadyWear` (the groove's shape on one
cross-section, extruded along x) and the :class:`tribofx.stepper.Stepper` (θ = 1:
one monolithic Newton in (u, λ, w₂, ζ); θ = 0: shape step, then contact).  Half
model (y ≥ 0), pushed against the ball by the bottom traction (F/2)/A e_z.

``regime``: ``small`` (Fig. 10) E = 200 GPa, ν = 0.3, R = 5 mm, F = 10 N (Hertz
a = 0.0555 mm, p₀ = 1.55 GPa), k = 10⁻⁷ mm³/(N·mm), V = 100 mm/s, L = 2π·10 mm,
T = 1000 s (groove ≈ 1.6·10⁻³ mm², half-width ≈ 0.23 mm); ``finite`` (Fig. 9)
E = 10 MPa (a/R = 0.3), k = 10⁻⁴.  ``graded`` (Fig. 10b): E and k × (1 + α max(1 −
d/h_L, 0)), d the depth of the worn point below the initial surface.  Mesh: block
[−27a, 27a] × [0, 27a] × [−27a, 0], Q1 hexahedra of size h = 0.45 a / 2^mesh in y, z
near the contact and h/2 along x.  ``wear_volume`` is the full groove area (mm³/mm),
``contact_radius`` the contact half-width across the groove, ``contact_half_length``
along x.  Runs under mpiexec (the cross-section unknowns are owned by rank 0).
Units: mm, N, s, MPa.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, TypeAlias, overload

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..forms import hyperelastic as hf
from ..forms import wear_groove as gf
from ..interfaces import Contact
from ..interfaces.steady_wear import SteadyWear
from ..meshes import halfspace as hs
from ..obstacles import rigid_sphere
from ..params import InputError, param
from ..references import hertz, rigid_groove_halfwidth
from ..stepper import Stepper, nominal_steps
from . import slow_time
from .slow_time import SchemeParams, check_scheme

if TYPE_CHECKING:
    import os
    from collections.abc import Mapping, Sequence
    from pathlib import Path

    import numpy.typing as npt
    import ufl.core.expr
    from dolfinx import mesh as dmesh
    from tqdm import tqdm

    from ..output import RunRecord
    from ..reports import NewtonReport
    from ..stepper import StepReport

    #: the case's meshes (:func:`groove_mesh`): block, its facet tags, cross-section, its
    #: facet tags, and the area of the block's bottom (mm²)
    GrooveMesh: TypeAlias = tuple[dmesh.Mesh, dmesh.MeshTags, dmesh.Mesh, dmesh.MeshTags, float]

__all__ = ["Model", "Params", "build", "doc", "groove_mesh", "initial_contact", "name", "plot",
           "progress_total", "resolved", "resumable", "run", "surface_data", "validate",
           "vtx_fields"]


@overload
def surface_data(contact: Contact, root: None = None) -> dict[str, npt.NDArray[Any]]: ...


@overload
def surface_data(contact: Contact, root: int) -> dict[str, npt.NDArray[Any]] | None: ...


def surface_data(contact: Contact, root: int | None = None
                 ) -> dict[str, npt.NDArray[Any]] | None:
    """Top-surface nodes: initial (x, y), nominal pressure p = −λ, active (in contact).

    ``active`` is the contact's own (:meth:`Contact.nodal_data`: the augmented traction
    T_N < 0), not the sign of λ, which at an open node is zero only to round-off.
    Owned nodes (``root=None``) or all nodes gathered on rank ``root`` (None elsewhere).
    """
    n = contact.Q.dofmap.index_map.size_local
    d = {"X": contact.X_sub[:n, :2], "p": np.maximum(-contact.lam_n.x.array[:n], 0.0),
         "active": contact.nodal_data()["active"]}
    if root is None:
        return d
    parts = contact.body.mesh.comm.gather(d, root=root)
    return None if parts is None else {k: np.concatenate([p[k] for p in parts]) for k in d}


REGIMES = {"small": {"E": 2.0e5, "k": 1.0e-7, "grade_depth": 0.01},
           "finite": {"E": 10.0, "k": 1.0e-4, "grade_depth": 0.3}}


def groove_mesh(comm: MPI.Comm, a: float, h: float, lz: float = 1.35,
                nc: Sequence[int] = (4, 5, 6)) -> GrooveMesh:
    """Block (on ``comm``) and cross-section (replicated) of the case, sizes in units of a."""
    gx, gy, gz = hs.grids(27 * a, 27 * a, 27 * a, h, 1.8 * a, 5.4 * a, lz * a, nc, hx=h / 2)
    msh, ft = hs.halfspace_block(comm, gx, gy, gz)
    sec, sft = hs.cross_section(MPI.COMM_SELF, gy, gz)
    return msh, ft, sec, sft, (gx[-1] - gx[0]) * gy[-1]


name = "wear-ball-halfspace"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "rigid ball sliding on an elastic half-space: quasi-steady wear groove (§5.3)"


@dataclass(frozen=True)
class Params(SchemeParams):
    """The parameters of ``wear-ball-halfspace`` (``--set KEY=VALUE``)."""

    dt: float = param(100.0, "s", "time step Δt (with tol: the first step)", lower=0.0)
    T: float = param(1000.0, "s", "end time", lower=0.0)
    regime: str = param(
        "small", "-",
        "material set: small (E=200 GPa) or finite (E=10 MPa)",
        choices=("small", "finite"))
    k: float | None = param(
        None, "mm^3/(N*mm)",
        "Archard coefficient of the substrate "
        "(default: 1e-7 small, 1e-4 finite)",
        lower=0.0, closed=True)
    V: float = param(100.0, "mm/s", "sliding speed", lower=0.0)
    E: float | None = param(
        None, "MPa",
        "Young's modulus of the substrate "
        "(default: 2e5 small, 10 finite)",
        lower=0.0)
    nu: float = param(0.3, "-", "Poisson's ratio", lower=-1.0, upper=0.5)
    R: float = param(5.0, "mm", "ball radius", lower=0.0)
    F: float = param(10.0, "N", "normal load on the ball", lower=0.0)
    L: float = param(2 * math.pi * 10.0, "mm", "sliding length per cycle (track length)", lower=0.0)
    mesh: int = param(
        0, "-",
        "refinement level: h = 0.45 a / 2^mesh at the contact",
        lower=0, upper=2, closed=True)
    law: str = param(
        "nominal", "-",
        "Archard law: nominal (eq. 14) or spatial (eqs. 15-16)",
        choices=("nominal", "spatial"))
    graded: bool = param(False, "-", "functionally graded surface layer (Fig. 10b)")
    grade_alpha: float = param(
        1.0, "-",
        "FGM: E and k at the surface = (1 + α) × substrate",
        lower=0.0, closed=True)
    grade_depth: float | None = param(
        None, "mm",
        "FGM layer thickness (default: 0.01 small, "
        "0.3 finite)",
        lower=0.0)
    max_cuts: int = param(6, "-", "step halvings allowed per step", lower=0, upper=20, closed=True)


def resolved(v: Params) -> Params:
    """Parameters with the regime defaults filled in."""
    return v.replace(**{key: val for key, val in REGIMES[v.regime].items()
                        if getattr(v, key) is None})


def validate(v: Params) -> None:
    """Check cross-parameter consistency."""
    v = resolved(v)
    assert v.k is not None and v.E is not None   # the regime's defaults, filled
    if v.dt > v.T:
        raise InputError(f"dt = {v.dt} s exceeds T = {v.T} s")
    check_scheme(v)
    a = hertz(v.F, v.R, v.E, v.nu).a
    if a > 0.5 * v.R:
        raise InputError(f"Hertz radius a = {a:.3g} mm > R/2: load too high for the ball")
    if v.L < 4 * a:
        raise InputError(f"L = {v.L:g} mm is shorter than the contact (4a = {4 * a:.3g} mm):"
                         " one pass per cycle is assumed")
    b = float(rigid_groove_halfwidth(v.k, v.F, v.R, v.V * v.T, v.L))
    if b > 5.4 * a:
        raise InputError(f"final groove half-width ≈ {b:.3g} mm exceeds the refined zone "
                         f"(5.4a = {5.4 * a:.3g} mm): reduce k, V or T, or increase L")


class Model(NamedTuple):
    """What :func:`build` assembles: the stepper of the block's body, contact and steady wear.

    ``hertz``: the unworn contact it starts from, {"a" (mm), "p0" (MPa), "delta" (the
    approach, mm), "h" (the contact element size, mm)}.
    """

    stepper: Stepper
    hertz: dict


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD, h: float | None = None,
          mesh: GrooveMesh | None = None,
          checkpoint: str | os.PathLike[str] | None = None) -> Model:
    """Body, contact, steady wear and stepper, the :class:`Model` of the case.

    ``h``, ``mesh``: contact element size (mm) and ``groove_mesh`` output (default:
    the case mesh).
    """
    v = resolved(v)
    assert v.k is not None and v.E is not None   # the regime's defaults, filled
    a, p0, delta = hertz(v.F, v.R, v.E, v.nu)[:3]
    h = 0.45 * a / 2 ** v.mesh if h is None else h
    msh, ft, sec, sft, area = groove_mesh(comm, a, h) if mesh is None else mesh
    mu, lmbda = hf.lame_parameters(v.E, v.nu)
    w3 = fem.Function(fem.functionspace(msh, ("Lagrange", 1, (3,))), name="shape_change_3d")
    # graded layer: a factor of the depth of the worn point below the surface
    fg: float | ufl.core.expr.Expr = 1.0
    if v.graded:
        depth = gf.material_depth(ufl.SpatialCoordinate(msh), w3)
        fg = gf.graded_factor(depth, v.grade_alpha, v.grade_depth)
    body = Body(msh, ft, hs.NAMES, "3d", ("neo-hookean", {"mu": mu * fg, "lmbda": lmbda * fg}),
                quadrature_degree=2, shape=w3, force_scale=v.F, stiffness=mu)
    body.add_dirichlet("ends", 0.0, component=0)
    body.add_dirichlet("sym", 0.0, component=1)
    body.add_dirichlet("far", 0.0, component=1)
    body.add_traction("bottom", ufl.as_vector([0.0, 0.0, 0.5 * v.F / area]))
    contact = Contact(body, "top", rigid_sphere(np.array([0.0, 0.0, v.R]), v.R),
                      rho_n=v.E / h)
    # shape rows to 1e-12 L (3.7e-12 mm): small against the worn-depth increment of one
    # explicit step (Δt k p V ≈ 1e-5 mm at Δt = 0.5 s), not only against the block
    wear = SteadyWear(contact, sec, sft, hs.SECTION_NAMES, hs.prolongation, v.k * fg,
                      v.V, v.L, law=v.law, aux=(v.E, 0.3),
                      fixed={"sym": [0], "far": [0], "bottom": [0, 1]},
                      scheme=v.scheme, rtol=1e-12)
    stepper = Stepper([body, contact, wear], wear, max_cuts=v.max_cuts,
                      checkpoint=checkpoint, name="groove", problem_class=wear.problem_class)
    return Model(stepper, {"a": a, "p0": p0, "delta": delta, "h": h})


def initial_contact(stepper: Stepper, info: Mapping[str, float],
                    verbose: bool = False) -> NewtonReport:
    """Unworn contact: the block starts lifted by the Hertz approach δ = a²/R.

    (The compression of the block by F/(2A)·H/E is negligible.)  Solved by the
    stepper's deformation problem (implicit: all unknowns, Δt = 0 keeps w₂ = 0).
    """
    stepper.wear.body.u.x.array.reshape(-1, 3)[:, 2] = info["delta"]
    rep = stepper.problem.solve_by_homotopy(verbose)
    stepper.problem.commit()
    return rep


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: nominal steps of dt to T (by time)."""
    return nominal_steps(v.T, v.dt)


def vtx_fields(stepper: Stepper) -> dict[str, list[fem.Function]]:
    """Displacement and 3D shape change (block), contact multiplier."""
    body = stepper.wear.body
    return {"displacement": [body.u, body.w], "contact": [stepper.wear.contact.lam_n]}


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """Groove profiles, pressure maps at t = 0 and final, pressure across the groove."""
    from ..plots.groove import plot_groove

    plot_groove(profile, outdir)


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False) -> Stepper:
    """Integrate the groove from t = 0 to T; record per-step histories.

    ``checkpoint``: directory of the per-step checkpoint (state and histories);
    ``resume``: continue from it (:mod:`tribofx.restart`).
    """
    v = resolved(v)
    for key in REGIMES[v.regime]:  # record the regime defaults actually used
        record.data["parameters"][key]["value"] = getattr(v, key)
    t_start = time.perf_counter()
    stepper, info = build(v, checkpoint=checkpoint)
    stepper.verbose = verbose
    wear, contact = stepper.wear, stepper.wear.contact
    comm = wear.body.mesh.comm
    n = {"u": wear.body.u, "lambda": contact.lam_n, "psi": wear.w2, "zeta": wear.zeta}
    n = {key: f.function_space.dofmap.index_map.size_global
         * f.function_space.dofmap.index_map_bs for key, f in n.items()}
    record.result("dofs", n, "-")
    record.result("psi_fraction", stepper.shape_unknown_fraction(), "- (share of Ψ and ζ)")
    record.result("hertz", info, "mm, MPa")
    # the groove (warp by w), the deformation (by u) and the contact pressure at every
    # step (ParaView time series)
    sr = slow_time.SlowTimeRecords(stepper, v, record, (
        "time", "wear_volume", "max_wear_depth", "contact_radius", "contact_half_length",
        "newton_iterations", "averaged_rate", "max_pressure", "dt", "error_estimate",
        "rejected"),
        vtx_fields(stepper), resume)
    record.data["num_dofs"] = sum(n.values())
    h, hist = sr.history, sr.hist
    prof = h.setdefault("prof", {"times": [], "profiles": [], "maps": []})
    residuals = record.data["newton_residuals"] = h.setdefault("newton_residuals", [])

    def log(t: float, its: int, dt: float, error: float | None = None,
            rejected: int = 0) -> None:
        d = surface_data(contact)
        X = d["X"][d["active"]]
        ext = [comm.allreduce(float(np.max(c, initial=0.0)), op=MPI.MAX)
               for c in (np.abs(X[:, 0]), X[:, 1], d["p"])]
        lp = wear.line_profile()
        sr.log(its, zip(hist, (t, 2 * wear.groove_area(), float(lp["depth"].max()),
                               ext[1], ext[0], its, 2 * wear.averaged_rate_integral(),
                               ext[2], dt, error, rejected)))
        g = surface_data(contact, root=0)
        if g is not None:
            prof["times"].append(t)
            prof["profiles"].append(lp["worn"].tolist())
            prof["maps"].append(np.column_stack([g["X"], g["p"]]).tolist())

    def on_step(st: Stepper, rep: StepReport) -> None:
        log(st.t, rep.iterations, rep.dt, rep.error, rep.rejected)
        residuals.append([float(x) for x in rep.reports[0].residuals])

    if not resume:
        log(0.0, initial_contact(stepper, info, verbose).iterations, 0.0)
    with sr.closing(report=lambda: _report(stepper, v, record, hist, prof,
                                               time.perf_counter() - t_start)):
        stepper.run(v.T, slow_time.step_controller(v, v.dt),
                    on_step=sr.written(on_step), progress=progress)
    return stepper


def _report(stepper: Stepper, v: Params, record: RunRecord, hist: Mapping[str, list[Any]],
            prof: Mapping[str, list[Any]], wall: float) -> None:
    units = {"time": "s", "wear_volume": "mm^3/mm (full groove cross-section area)",
             "max_wear_depth": "mm", "contact_radius": "mm (half-width across the groove)",
             "contact_half_length": "mm (along the sliding direction)",
             "newton_iterations": "-", "averaged_rate": "mm^3/(mm*s) ((2/L) ∫ k p v dA)",
             "max_pressure": "MPa (nominal)", "dt": "s",
             "error_estimate": "mm (per step, error control)", "rejected": "-"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    record.result("accepted_steps", len(hist["time"]) - 1, "-")
    record.result("rejected_steps", int(sum(hist["rejected"])), "-")
    wear = stepper.wear
    w = wear.line_profile()["worn"]
    record.result("final_profile", np.vstack([w[::-1] * [-1, 1], w[1:]]).tolist(),
                  "mm (worn cross-section (y, z), both halves)")
    y, pint = wear.averaged_pressure()
    record.result("final_pressure_integral", np.column_stack([y, pint]).tolist(),
                  "mm, N/mm (y, ∫ p dx)")
    record.result("wall_time_solve", wall, "s")
    d = surface_data(wear.contact, root=0)
    if d is None:
        return
    on = np.abs(d["X"][:, 0]) < 1e-9
    o = np.argsort(d["X"][on, 1])
    px0 = np.column_stack([d["X"][on, 1][o], d["p"][on][o]]).tolist()
    record.result("final_pressure_x0", px0, "mm, MPa (y, p at x = 0)")
    record.profile = {**hist, **prof, "scheme": v.scheme, "graded": v.graded,
                      "R": v.R, "pressure_x0": px0,
                      "pressure_integral": np.column_stack([y, pint]).tolist()}
