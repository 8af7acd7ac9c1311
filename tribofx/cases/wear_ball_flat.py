"""Elastic ball on a rigid flat: quasi-steady-state sliding wear (chapter §5.2): ``wear-ball-flat``.

An elastic ball (radius R, neo-Hookean with E, ν; small strains here) is pressed
by a normal force F against a rigid plane z = 0 that slides by at speed V in the
x direction.  In the frame of the ball the ball material is at rest, the
deformation problem is a steady frictional contact problem (Eulerian slip,
eqs. 26–27: v_T = −V e_x, fixed direction, Coulomb μ: sliding everywhere in
contact), and the ball wears by the dissipation form of Archard's law (eqs.
13–14) Ẇ = K T_T·v_T, K = k/μ, i.e. Ẇ = k p V per unit area.  The shape
evolution (28) is integrated on the initial mesh by the implicit (θ = 1,
monolithic Newton in u, λ_N, λ_T, w, ζ) or explicit (θ = 0) scheme: a
:class:`tribofx.body.Body` with a shape field, a :class:`tribofx.interfaces.Contact`
with Eulerian slip, a :class:`tribofx.interfaces.Wear` on it and the slow time by
:class:`tribofx.stepper.Stepper`.  A step that fails (Newton divergence, force
not reached or an inverted cell) is halved (``max_cuts``) and the step size is
doubled back as soon as the time is aligned with the coarser step.

Model: quarter ball (the lower hemisphere cut by the symmetry plane y = 0 that
contains the sliding direction), :func:`tribofx.meshes.wear_ball.quarter_ball`,
P1 tetrahedra of size h = a_H/(2·2^mesh) (or ``h_contact``) within r_fine = 1.25 a_T (a_T the
rigid-cap scar radius at T, at least 2 a_H) of the initial contact point, R/4
far away.  Loading (chapter: at the mid-plane, which moves vertically as a
rigid plane): in the ball frame the mid-plane z = R is clamped (u = 0, it also
supports the friction force and its moment) and the rigid flat is translated
vertically by δ (``approach``) so that the contact force of the half contact is
F/2 to 10⁻⁸ (:class:`tribofx.hold.Hold`): by default δ is an
unknown of the step's Newton solve, with the force equation beside the system
(``force_control=bordered``, :class:`tribofx.bordered.Border`; 3–4 iterations a
step); ``secant`` finds it by the secant iteration of
:meth:`tribofx.continuation.Continuation.reach` around complete Newton solves
(3–4 trials of 2–3 iterations, 7–9 a step; more on a first step).  A uniform traction on a
free mid-plane is not used: the friction moment μ F R would tilt the ball.
Symmetry: u_y = 0, w_y = 0 on y = 0; the shape change has no normal motion on
the mid-plane (w_z = 0).

Parameters (chapter §5.2: R = 5 mm, E = 100 GPa, ν = 0.3, F = 100 N, Hertz
radius a_H = 0.15 mm, p₀ = 2.1 GPa, T = 1000 s, implicit Δt = 100 s).  Left
open by the chapter (Stupkiewicz 2013), chosen here: V = 10 mm/s (a typical
ball-on-disc sliding speed), μ = 0.4 (dry steel on steel, 0.3–0.5), k = 10⁻⁸
mm³/(N·mm) (mild-wear range of steels, 10⁻⁹–10⁻⁷), so that the sliding
distance s = V T = 10⁴ mm gives a scar of radius a = (4kFRs/π)^{1/4} = 0.50 mm
≈ 3.3 a_H and a uniform pressure of F/(πa²) ≈ 127 MPa at T.

Rigid-cap Archard law (the late-time reference,
:func:`tribofx.references.rigid_cap_radius`): once the scar radius a is well
beyond a_H the elastic approach (∼ a_H²/R) is small against the worn depth, the
worn surface is a plane and the ball wears as a rigid sphere truncated flat,
a(s) = (4kFRs/π)^{1/4}, at the uniform pressure F/(πa²).

Recorded per step: ``time``, ``wear_volume`` (full ball, mm³), ``max_wear_depth``,
``contact_radius`` (from the active contact area A of the half disc, √(2A/π)),
``scar_radius`` (√(2Rh − h²) from the max depth h, the flat-scar radius),
``pressure_ratio`` (max/min nodal pressure over the nodes within 0.7 of the
contact radius), ``approach`` (flat position δ, mm), ``newton_iterations``
(all trials of the force iteration), ``wear_rate_integral`` (full ball,
mm³/s), ``dt``; ``final_profile``: worn contact boundary along the symmetry
line y = 0 ([x, z] points, mm).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np
from dolfinx import mesh as dmesh
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..hold import Hold
from ..interfaces import Contact, Wear
from ..meshes.user import boundary_facet_size, read_user_mesh
from ..meshes.wear_ball import NAMES, quarter_ball
from ..obstacles import rigid_plane
from ..params import InputError, param
from ..references import composite_modulus, hertz, rigid_cap_depth, rigid_cap_radius
from ..stepper import Stepper, nominal_steps
from . import slow_time
from .slow_time import FilteredSchemeParams, check_scheme

if TYPE_CHECKING:
    import os
    from collections.abc import Callable, Mapping
    from pathlib import Path

    import numpy.typing as npt
    from dolfinx import fem
    from tqdm import tqdm

    from ..obstacles import AnalyticObstacle
    from ..output import RunRecord, SubRecord
    from ..stepper import StepReport

__all__ = ["MODEL_FRACTION", "Model", "Params", "build", "contact_plane", "doc",
           "late_time_exponent", "measures", "mesh_sizes", "name", "plot", "progress_total",
           "resumable", "run", "symmetry_line", "validate", "vtx_fields"]


MODEL_FRACTION = 0.5  # the quarter ball carries half of the contact (and of the wear)


name = "wear-ball-flat"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "elastic ball worn by a sliding rigid flat, quasi-steady state, quarter model (§5.2)"


@dataclass(frozen=True)
class Params(FilteredSchemeParams):
    """The parameters of ``wear-ball-flat`` (``--set KEY=VALUE``)."""

    dt: float = param(100.0, "s", "time step Δt (with tol: the first step)", lower=0.0)
    T: float = param(1000.0, "s", "end time", lower=0.0)
    k: float = param(
        1e-8, "mm^3/(N*mm)",
        "Archard coefficient (rate = k p V)",
        lower=0.0, closed=True)
    V: float = param(10.0, "mm/s", "sliding speed of the rigid flat", lower=0.0)
    E: float = param(1e5, "MPa", "Young's modulus of the ball", lower=0.0)
    nu: float = param(0.3, "-", "Poisson's ratio", lower=-1.0, upper=0.5)
    R: float = param(5.0, "mm", "ball radius", lower=0.0)
    F: float = param(100.0, "N", "normal force on the full ball", lower=0.0)
    friction: float = param(0.4, "-", "Coulomb coefficient μ (K = k/μ)", lower=0.0)
    mesh: int = param(
        0, "-",
        "refinement level: contact-zone element size a_H/(2·2^mesh)",
        lower=0, upper=3, closed=True)
    h_contact: float = param(
        0.0, "mm",
        "contact-zone element size; 0: a_H/(2·2^mesh) (the chapter's mesh: 0.125)",
        lower=0.0, closed=True)
    force_control: str = param(
        "bordered", "-",
        "the flat's position δ: an unknown of each Newton solve (bordered) or found "
        "by a secant of complete solves (secant)",
        choices=("bordered", "secant"))
    max_cuts: int = param(8, "-", "step halvings allowed per step", lower=0, upper=20, closed=True)
    mesh_file: str = param(
        "", "-",
        "your own ball: a 3D gmsh .msh of the half body y ≥ 0 with physical groups "
        "contact (the surface the flat wears), loaded (the clamped mid-plane) and "
        "symmetry_y (on y = 0); its lowest contact point is moved to the origin; "
        "replaces mesh (R still sets the scar-radius measure and the mesh-size check)")


def validate(v: Params) -> None:
    """Check cross-parameter consistency."""
    if v.dt > v.T:
        raise InputError(f"time step {v.dt} s exceeds T = {v.T} s")
    check_scheme(v)
    if v.error_filter and v.force_control != "bordered":
        raise InputError("error_filter holds the force by the border: "
                         "force_control=bordered")
    if v.mesh_file and v.h_contact:
        raise InputError("h_contact sets the built mesh: not with mesh_file")
    aH = hertz(v.F, v.R, v.E, v.nu).a
    if aH > 0.2 * v.R:
        raise InputError(f"load too large for small strains: a_H/R = {aH / v.R:.2f}")
    aT = mesh_sizes(v)[2] / 1.25
    if aT > 0.6 * v.R:
        raise InputError(f"scar radius at T ({aT:.3g} mm) beyond 0.6 R: reduce k, V or T")


def mesh_sizes(v: Params) -> tuple[float, float, float]:
    """(h_fine, h_coarse, r_fine) in mm; see the module docstring."""
    aH = hertz(v.F, v.R, v.E, v.nu).a
    aT = max(float(rigid_cap_radius(v.k, v.F, v.R, v.V * v.T)), 2 * aH)
    h = v.h_contact or aH / (2 * 2 ** v.mesh)
    return h, v.R / 4, 1.25 * aT


class Model(NamedTuple):
    """What :func:`build` assembles: the stepper with its load hold.

    ``h_fine``: the element size of the contact zone (mm).
    """

    stepper: Stepper
    h_fine: float


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD,
          checkpoint: str | os.PathLike[str] | None = None) -> Model:
    """Body, contact, wear, stepper and force control of the case (not yet loaded).

    Returns the :class:`tribofx.stepper.Stepper`; its ``control`` positions the
    flat so that the contact force of the half contact is F/2.
    """
    h_fine, h_coarse, r_fine = mesh_sizes(v)
    if v.mesh_file:
        # (without ``cells``: the mesh, its facet tags and their names)
        msh, ft, names = cast("tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int]]",
                              read_user_mesh(v.mesh_file, comm, 3, tuple(NAMES)))
        h_fine = _user_ball(msh, ft, names, v)
    else:
        msh, ft = quarter_ball(v.R, h_fine, h_coarse, r_fine, comm)
        names = NAMES
    mu, lmbda = lame_parameters(v.E, v.nu)
    # ball frame: the ball material is at rest, the flat moves at V e_x (eqs. 26–27)
    body = Body(msh, ft, names, "3d", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
                shape=True, aux=(v.E, 0.3), velocity=np.zeros(3))
    # the mid-plane is the rigid holder: clamped in the ball frame, the flat moves
    body.add_dirichlet("loaded", np.zeros(3))
    body.add_dirichlet("symmetry_y", 0.0, component=1)
    body.add_shape_dirichlet("symmetry_y", 1)
    body.add_shape_dirichlet("loaded", 2)
    contact = Contact(body, "contact", rigid_plane(np.zeros(3), np.array([0.0, 0, 1])),
                      rho_n=v.E / h_fine, friction=v.friction, slip="eulerian",
                      V_master=(v.V, 0.0, 0.0), dtau=1.0)
    wear = Wear(contact, k=v.k, speed=v.V, scheme=v.scheme)
    # the flat's position is state of the contact (its counterpart's state fields):
    # restored by a cut step and by a resume
    stepper = Stepper([body, contact, wear], wear, max_cuts=v.max_cuts,
                      checkpoint=checkpoint, name="wear_ball")
    offset = cast("AnalyticObstacle", contact.counterpart).offset   # the rigid flat's
    Es = composite_modulus(v.E, v.nu)
    a_H = hertz(v.F, v.R, v.E, v.nu).a

    def predictor(dt: float) -> float:
        # rigid cap: h² ∝ s, so sliding V Δt more adds rigid_cap_depth(V Δt)² to h²
        h = wear.max_depth()
        dh2 = float(rigid_cap_depth(v.k, v.F, v.R, v.V * dt)) ** 2
        return float(offset.value[2]) + math.sqrt(h * h + dh2) - h

    def stiffness(dt: float) -> float:
        # flat punch of radius a: compliance πa/(2E*) per unit pressure, in series
        # (implicit step) with the wear compliance k V Δt
        a = max(math.sqrt(contact.measures()[0] / (MODEL_FRACTION * math.pi)), a_H)
        c_wear = v.k * v.V * dt if wear.scheme.implicit else 0.0
        return MODEL_FRACTION * math.pi * a * a / (math.pi * a / (2 * Es) + c_wear)

    search = Continuation(stepper.problem, ConstantParameter(offset, 2),
                          response=lambda: float(contact.force()[2]), rtol=1e-8,
                          max_trials=12)
    stepper.hold = Hold(search, MODEL_FRACTION * v.F, step_guess=predictor,
                        step_slope=stiffness,
                        border=((contact.force_functional(2), contact.sub)
                                if v.force_control == "bordered" else None))
    return Model(stepper, h_fine)


def _user_ball(msh: dmesh.Mesh, ft: dmesh.MeshTags, names: Mapping[str, int],
               v: Params) -> float:
    """Move a user's ball so that its lowest contact point is the origin; its h there.

    The symmetry group must lie on y = 0 (one-line error otherwise).  The
    returned element size is the mean size of the contact facets within the
    Hertz radius a_H of that point (the augmentation ρ_N = E/h).
    """
    comm = msh.comm
    x = msh.geometry.x
    fdim = msh.topology.dim - 1
    contact = np.unique(dmesh.entities_to_geometry(
        msh, fdim, ft.find(names["contact"]), False).ravel())
    z = x[contact, 2] if len(contact) else np.array([np.inf])
    zmin = comm.allreduce(float(z.min()), op=MPI.MIN)
    i = int(np.argmin(z))
    lowest = x[contact[i]].copy() if len(contact) and z[i] == zmin else None
    lowest = next(p for p in comm.allgather(lowest) if p is not None)
    x[:, 0] -= lowest[0]
    x[:, 2] -= zmin
    sym = np.unique(dmesh.entities_to_geometry(
        msh, fdim, ft.find(names["symmetry_y"]), False).ravel())
    off = comm.allreduce(float(np.max(np.abs(x[sym, 1]), initial=0.0)), op=MPI.MAX)
    if off > 1e-9 * v.R:
        raise InputError(f"mesh file {v.mesh_file!r}: group 'symmetry_y' is not on "
                         f"the plane y = 0 (|y| up to {off:.3g} mm)")
    aH = hertz(v.F, v.R, v.E, v.nu).a
    return boundary_facet_size(msh, ft, names["contact"], near=(np.zeros(3), aH))


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: nominal steps of dt to T (by time)."""
    return nominal_steps(v.T, v.dt)


def measures(stepper: Stepper, v: Params) -> dict[str, float]:
    """Contact radius, flat-scar radius, pressure ratio, max depth, full-ball worn volume."""
    wear = stepper.wear
    comm = wear.body.mesh.comm
    d = wear.nodal_shape_data()
    area = comm.allreduce(float(np.sum(d["weight"][d["active"]])), op=MPI.SUM)
    a_c = math.sqrt(area / (MODEL_FRACTION * math.pi))
    h = comm.allreduce(float(np.max(d["depth"], initial=0.0)), op=MPI.MAX)
    a_s = math.sqrt(max(2 * v.R * h - h * h, 0.0))
    r = np.linalg.norm(d["x"][:, :2], axis=1)
    inner = d["active"] & (r < 0.7 * a_c)
    pmax = comm.allreduce(float(np.max(d["p"][inner], initial=0.0)), op=MPI.MAX)
    pmin = comm.allreduce(float(np.min(d["p"][inner], initial=np.inf)), op=MPI.MIN)
    return {"contact_radius": a_c, "scar_radius": a_s, "max_wear_depth": h,
            "pressure_ratio": pmax / pmin if pmin > 0 else math.inf,
            "wear_volume": wear.worn_volume() / MODEL_FRACTION,
            "wear_rate_integral": wear.wear_rate_integral() / MODEL_FRACTION}


def symmetry_line(stepper: Stepper, v: Params) -> dict[str, npt.NDArray[np.float64]] | None:
    """Worn and deformed contact boundary along y = 0 near the contact, on rank 0 (else None).

    Returns a dict of arrays sorted by X̂_x: X_worn, x (deformed), p (pressure).
    """
    d = stepper.wear.gather_shape()
    if d is None:
        return None
    r_fine = mesh_sizes(v)[2]
    sel = (np.abs(d["X_hat"][:, 1]) < 1e-9 * v.R) & (d["X_hat"][:, 2] < 0.5 * v.R) \
        & (np.abs(d["X_hat"][:, 0]) <= 2 * r_fine)
    return {"X_worn": d["X_worn"][sel], "x": d["x"][sel], "p": d["p"][sel]}


def contact_plane(stepper: Stepper) -> npt.NDArray[np.float64] | None:
    """(x, y, p) of all contact-surface nodes within the active zone, on rank 0 (else None)."""
    d = stepper.wear.gather_shape()
    if d is None:
        return None
    a = d["active"]
    return np.column_stack([d["x"][a, 0], d["x"][a, 1], d["p"][a]])


def run(v: Params, record: RunRecord | SubRecord, progress: tqdm | None = None,
        verbose: bool = False,
        on_step: Callable[[Stepper, StepReport], object] | None = None,
        comm: MPI.Comm = MPI.COMM_WORLD, t_stop: float | None = None,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False) -> Stepper:
    """Integrate the wear of the ball from t = 0 to T; record per-step histories.

    ``on_step(stepper, report)``, if given, is called after every accepted step;
    ``t_stop`` < T ends the run early (on the mesh built for T).  ``checkpoint``:
    directory of the per-step checkpoint (state and histories); ``resume``:
    continue from it (:mod:`tribofx.restart`).  Returns the stepper.
    """
    t_wall = time.perf_counter()
    stepper, h_fine = build(v, comm=comm, checkpoint=checkpoint)
    assert stepper.hold is not None     # the force hold of build()
    stepper.verbose = stepper.hold.search.verbose = verbose
    record.result("shape_unknown_fraction", stepper.shape_unknown_fraction(), "-")
    cast("Any", record).stepper = stepper   # (for the caller: tests read the stepper there)
    comm = stepper.comm
    record.result("h_contact_zone", h_fine, "mm")
    keys = ("time", "dt", "approach", "wear_volume", "max_wear_depth", "contact_radius",
            "scar_radius", "pressure_ratio", "newton_iterations", "wear_rate_integral",
            "error_estimate", "rejected")
    # the worn shape (warp by w), the deformation (by u) and the contact pressure at
    # every step (ParaView time series)
    sr = slow_time.SlowTimeRecords(stepper, v, record, keys, vtx_fields(stepper),
                                   resume)
    h = sr.history
    state = h.setdefault("state", {"profiles": [], "initial_plane": None})
    residuals = h.setdefault("newton_residuals", [])
    residuals_all = h.setdefault("newton_residuals_all", [])
    record.data["newton_residuals"] = residuals
    record.data["newton_residuals_all"] = residuals_all
    offset = stepper.wear.contact.counterpart.offset

    def log(t: float, its: int, dt: float, error: float | None = None,
            rejected: int = 0) -> None:
        m = measures(stepper, v)
        sr.log(its, (("time", t), ("dt", dt), ("newton_iterations", its),
                     ("approach", float(offset.value[2])), *m.items(),
                     ("error_estimate", error), ("rejected", rejected)))
        line = symmetry_line(stepper, v)
        if comm.rank == 0:
            assert line is not None     # gathered on rank 0
            state["profiles"].append((t, line["X_worn"][:, [0, 2]].tolist()))

    def step_done(st: Stepper, rep: StepReport) -> None:
        log(st.t, rep.iterations, rep.dt, rep.error, rep.rejected)
        residuals.append([float(x) for x in rep.reports[-1].residuals])
        residuals_all.append([[float(x) for x in r.residuals] for r in rep.reports])
        if on_step is not None:
            on_step(st, rep)

    if not resume:
        reports = stepper.hold.solve(
            guess=hertz(v.F, v.R, v.E, v.nu).delta).reports
        plane = contact_plane(stepper)
        state["initial_plane"] = None if plane is None else plane.tolist()
        log(0.0, int(sum(r.iterations for r in reports)), 0.0)
    T = v.T if t_stop is None else min(t_stop, v.T)
    with sr.closing(report=lambda: _report(stepper, v, record, sr.hist, state,
                                               time.perf_counter() - t_wall)):
        stepper.run(T, slow_time.step_controller(v, v.dt),
                    on_step=sr.written(step_done), progress=progress)
    return stepper


def late_time_exponent(time_s: npt.ArrayLike, radius: npt.ArrayLike, V: float,
                       t_min: float) -> float:
    """Least-squares slope of log a against log s = V t over the steps with t ≥ t_min."""
    t = np.asarray(time_s, dtype=float)
    a = np.asarray(radius, dtype=float)
    sel = t >= t_min
    if np.count_nonzero(sel) < 2:
        return math.nan
    return float(np.polyfit(np.log(V * t[sel]), np.log(a[sel]), 1)[0])


def _report(stepper: Stepper, v: Params, record: RunRecord | SubRecord,
            hist: Mapping[str, list[Any]], state: Mapping[str, Any], wall: float) -> None:
    units = {"time": "s", "dt": "s", "approach": "mm (flat position)",
             "wear_volume": "mm^3 (full ball)",
             "max_wear_depth": "mm", "contact_radius": "mm", "scar_radius": "mm",
             "pressure_ratio": "-", "newton_iterations": "-",
             "wear_rate_integral": "mm^3/s (full ball)",
             "error_estimate": "mm (per step, error control)", "rejected": "-"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    record.result("rejected_steps", int(sum(hist["rejected"])), "-")
    assert stepper.hold is not None     # the force hold of build()
    record.result("force_fallbacks", stepper.hold.fallbacks, "-")
    record.result("wall_time", stepper.comm.allreduce(wall, op=MPI.MAX), "s")
    record.result("steps", len(hist["time"]) - 1, "-")
    s = v.V * np.asarray(hist["time"])
    a_cap = rigid_cap_radius(v.k, v.F, v.R, s)
    record.result("rigid_cap_radius", a_cap.tolist(), "mm")
    a_H = hertz(v.F, v.R, v.E, v.nu).a
    if a_cap[-1] < 2 * a_H:   # the law's range: a scar well beyond the Hertz contact
        record.warn(f"rigid_cap_radius ({a_cap[-1]:.3g} mm at T) is outside the rigid-cap "
                    f"law's range: it needs a scar well beyond the Hertz radius "
                    f"a_H = {a_H:.3g} mm (here the ball is too soft or T too short)")
    record.result("archard_volume", (v.k * v.F * s).tolist(), "mm^3 (k F V t)")
    for key in ("contact_radius", "scar_radius"):
        record.result(f"{key}_exponent_late",
                      late_time_exponent(hist["time"], hist[key], v.V, 0.4 * v.T),
                      "-")
    line = symmetry_line(stepper, v)
    plane = contact_plane(stepper)
    if line is not None:
        record.result("final_profile", line["X_worn"][:, [0, 2]].tolist(),
                      "mm ([x, z] of the worn boundary on y = 0)")
        record.result("final_profile_deformed", line["x"][:, [0, 2]].tolist(), "mm")
        record.result("final_pressure_symmetry_line", line["p"].tolist(), "MPa")
        initial = state["initial_plane"]
        record.profile = {**hist, "profiles": state["profiles"],
                          "initial_plane": None if initial is None else np.asarray(initial),
                          "final_plane": plane,
                          "scheme": v.scheme, "dt": v.dt, "R": v.R, "k": v.k,
                          "F": v.F, "V": v.V}


def vtx_fields(stepper: Stepper) -> dict[str, list[fem.Function]]:
    """Fields for ParaView: displacement and shape change (bulk), contact multiplier."""
    return slow_time.wear_fields(stepper.wear)


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """``pressure.png``, ``profiles.png`` and ``scar.png`` (:func:`tribofx.plots.wear`)."""
    from ..plots.wear import plot_wear_ball

    plot_wear_ball(profile, outdir)
