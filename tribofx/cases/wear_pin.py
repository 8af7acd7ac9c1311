"""Pin-on-flat finite wear (chapter §4.4, Figs. 2–4): case ``wear-pin``.

A neo-Hookean plane-strain pin of width W and height H with a rounded tip
(circular arc of radius R_tip through the lowest point) is pressed by a uniform
traction q on its top face onto a rigid plane y = 0 that slides at speed V.
Contact is frictionless; the lateral faces x = ±W/2 are constrained laterally
(u_x = 0) and free vertically.  Archard wear, nominal rate Ẇ = k p V (eq. 14
in pressure form), changes the shape of the tip; the shape evolution (28) is
integrated to t = T by the explicit (θ = 0) or implicit (θ = 1) scheme on the
initial mesh: a :class:`tribofx.body.Body` with a shape field, a
:class:`tribofx.interfaces.Contact` on the rigid plane, a
:class:`tribofx.interfaces.Wear` on it, the slow time by :class:`tribofx.stepper.Stepper`.

Default data (the chapter leaves them to Stupkiewicz 2013; chosen in its
spirit): W = H = 2 mm, R_tip = 4 mm (tip height 0.127 mm), q = 2 MPa
(4 N/mm), V = 10 mm/s, k = 5·10⁻⁶ mm³/(N·mm), T = 1000 s, so that the worn
area k q W V T = 0.2 mm² per mm (mean depth 0.1 mm) flattens most of the tip.
E = 640 MPa (small-deformation regime: initial Hertz half-width 0.17 mm) to
E = 10 MPa (finite deformation, full contact), ν = 0.3.  Options: ``law``
(nominal Ẇ = k p V, eq. 14, or spatial Ẇ = (k/J) p V, eqs. 15–16) and a wear
coefficient graded with the worn depth d, k(d) = k max(1 + k_grad d, 0).  The structured mesh
has n × n squares (split in triangles), n = 10·2^mesh.

Friction (``friction`` = μ > 0, eqs. 13–14): the wear rate is driven by the
frictional dissipation, Ẇ = (k/μ) T_T·v_T, which equals k p V in sliding.
``mode=steady``: steady sliding of the plane at V with the Eulerian slip
velocity (v = F V − V_plane, eqs. 26–27; the pin is at rest, so v_T = −V e_x).
``mode=cyclic`` (μ > 0 required): time-scale separation (§4.2, eqs. 21–23, the
reciprocating pin-on-flat test of §5.1): per slow step one fast reciprocating
cycle of the plane (peak-to-peak ``stroke`` 2A, ``fast_steps`` sub-steps, a
run-in stage from −A first, Lagrangian friction), wear increment accumulated
over the cycle and averaged, shape updated by the θ-scheme on the slow time (θ
= 0 ``explicit``, θ = 1 ``implicit`` by Picard iteration; see
:mod:`tribofx.stepper`).  A slow step stands for ``cycles_per_step`` cycles,
Δt = cycles_per_step · 2 stroke / V (0: Δt = ``dt``).

``study=dt`` (Fig. 3 and Fig. 4 of the chapter): for the given E and each mesh
level of ``study_meshes`` (default: ``mesh``), the explicit and the implicit
scheme are run to T with every Δt of ``study_dts`` (default 200, 100, 50, 20,
10, 5 s), plus an implicit reference run with Δt = ``study_ref_dt`` (default
T/1280 = 0.78125 s, as in the chapter; ``study_ref=richardson``: 2 p(Δt_r) −
p(2 Δt_r) of two implicit runs instead; ``study_schemes`` may add ``bdf2``, and the
reference is then a BDF2 run at Δt_r).  The error of a run is the Euclidean
norm (as in the chapter) of the difference of the final worn nodal positions
X̂ + w on Γ̂_c from the reference (mm; the max nodal distance is also stored).
A run is flagged unstable (:func:`tribofx.studies.wear_dt_study.run_dt_study`) if it fails
(Newton divergence or an inverted mesh at its nominal Δt: explicit runs get no
step cutting) or if its error is dominated by the node-to-node alternating
(checkerboard) mode (:func:`tribofx.studies.wear_stability.oscillation_ratio` of the
vertical error > ``OSCILLATION_TOL``), or (explicit) if Δt exceeds the critical
step Δt_cr of the mesh (:func:`tribofx.studies.wear_stability.pin_critical_step`, also
reported).  Writes ``error_vs_dt.png``,
``profiles.png`` and the ``study_*`` results in summary.json.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple, cast

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms import wear as wf
from ..forms.hyperelastic import lame_parameters
from ..interfaces import Contact, Wear
from ..laws import Law
from ..meshes.pin import NAMES, pin_body, tip_height
from ..meshes.user import read_user_mesh
from ..obstacles import rigid_plane
from ..params import InputError, number_list, param
from ..references import hertz
from ..stepper import ReciprocatingCycle, Stepper, nominal_steps
from . import slow_time
from .slow_time import SCHEMES, SchemeParams, check_scheme
from .user_pin import place_user_pin, user_pin_approach

if TYPE_CHECKING:
    import os
    from collections.abc import Callable, Mapping
    from pathlib import Path

    from dolfinx import mesh as dmesh
    from tqdm import tqdm

    from ..output import RunRecord, SubRecord
    from ..stepper import StepReport

__all__ = ["Model", "Params", "build", "doc", "load_up", "n_elements", "name", "plot",
           "progress_total", "resumable", "run", "slow_step", "study_lists", "study_schemes",
           "validate", "vtx_fields"]


name = "wear-pin"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "plane-strain pin with rounded tip worn on a sliding rigid flat (§4.4)"


@dataclass(frozen=True)
class Params(SchemeParams):
    """The parameters of ``wear-pin`` (``--set KEY=VALUE``)."""

    dt: float = param(200.0, "s", "time step Δt", lower=0.0)
    T: float = param(1000.0, "s", "end time", lower=0.0)
    k: float = param(
        5e-6, "mm^3/(N*mm)",
        "Archard coefficient (rate = k p V)",
        lower=0.0, closed=True)
    V: float = param(10.0, "mm/s", "sliding speed of the rigid plane", lower=0.0, closed=True)
    E: float = param(640.0, "MPa", "Young's modulus", lower=0.0)
    nu: float = param(0.3, "-", "Poisson's ratio", lower=-1.0, upper=0.5)
    mesh: int = param(
        1, "-",
        "refinement level: n × n structured mesh, n = 10·2^mesh",
        lower=0, upper=4, closed=True)
    q: float = param(2.0, "MPa", "uniform traction on the top face", lower=0.0)
    W: float = param(2.0, "mm", "pin width", lower=0.0)
    H: float = param(2.0, "mm", "pin height", lower=0.0)
    R_tip: float = param(4.0, "mm", "tip radius (0: flat-ended punch)", lower=0.0, closed=True)
    law: str = param(
        "nominal", "-",
        "Archard law: nominal (eq. 14) or spatial (eqs. 15-16)",
        choices=("nominal", "spatial"))
    k_grad: float = param(
        0.0, "1/mm",
        "depth gradient g of the wear coefficient, k(d) = k max(1 + g d, 0)")
    k_law: str = param(
        "constant", "-",
        "wear coefficient against the contact pressure: "
        "constant (Archard) or pressure, k(p) = k (1 + (p/k_ps)^k_m) (mild to severe)",
        choices=("constant", "pressure"))
    k_ps: float = param(1.0, "MPa", "transition pressure of k_law=pressure", lower=0.0)
    k_m: float = param(2.0, "-", "exponent of k_law=pressure", lower=0.0, upper=10.0, closed=True)
    friction: float = param(
        0.0, "-",
        "Coulomb coefficient μ (> 0: dissipation-driven wear, K = k/μ)",
        lower=0.0, closed=True)
    mode: str = param(
        "steady", "-",
        "steady sliding (Eulerian slip) or cyclic (reciprocating, time-scale separation)",
        choices=("steady", "cyclic"))
    stroke: float = param(1.0, "mm", "cyclic: peak-to-peak stroke 2A of the flat", lower=0.0)
    fast_steps: int = param(
        8, "-",
        "cyclic: fast sub-steps per cycle (multiple of 4)",
        lower=4, upper=100000, closed=True)
    cycles_per_step: float = param(
        0.0, "-",
        "cyclic: cycles per slow step (0: Δt = dt)",
        lower=0.0, closed=True)
    max_cuts: int = param(6, "-", "step halvings allowed per step", lower=0, upper=20, closed=True)
    study: str = param(
        "none", "-",
        "none: one run; dt: explicit and implicit error versus Δt study (Figs. 3-4)",
        choices=("none", "dt"))
    study_dts: str = param("200,100,50,20,10,5", "s", "study=dt: comma-separated time steps")
    study_meshes: str = param(
        "", "-",
        "study=dt: comma-separated mesh levels (n = 10·2^level; empty: mesh)")
    study_ref_dt: float = param(
        0.78125, "s",
        "study=dt: time step of the implicit reference run",
        lower=0.0)
    study_ref: str = param(
        "fine", "-",
        "study=dt: reference = implicit run at study_ref_dt (fine) or Richardson "
        "2 p(study_ref_dt) - p(2 study_ref_dt)",
        choices=("fine", "richardson"))
    study_schemes: str = param(
        "explicit,implicit", "-",
        "study=dt: schemes compared (explicit, implicit, bdf2; with bdf2 the "
        "reference is a BDF2 run)")
    study_critical: bool = param(
        True, "-",
        "study=dt: also compute the explicit critical step of each mesh")
    mesh_file: str = param(
        "", "-",
        "your own pin: a 2D gmsh .msh with physical groups contact (the tip), top "
        "(loaded), sides (x fixed); replaces W, H, R_tip, mesh (lowest tip point "
        "moved to y = 0)")


def validate(v: Params) -> None:
    """Check cross-parameter consistency."""
    if v.mesh_file and v.study != "none":
        raise InputError("mesh_file works with study=none only")
    R = v.R_tip
    if R and R < v.W / 2:
        raise InputError(f"R_tip = {R} mm must be 0 (flat) or >= W/2 = {v.W / 2} mm")
    if tip_height(v.W / 2, R) >= 0.5 * v.H:
        raise InputError("the rounded tip must be lower than half the pin height")
    if v.mode == "cyclic":
        if v.friction <= 0:
            raise InputError("mode=cyclic needs friction > 0 (Lagrangian Coulomb friction)")
        if v.fast_steps % 4:
            raise InputError(f"fast_steps = {v.fast_steps} must be a multiple of 4")
        if v.V <= 0:
            raise InputError("mode=cyclic needs V > 0")
    check_scheme(v)
    if v.tol > 0 and v.study == "dt":
        raise InputError("tol > 0 (error control) is not for study=dt (fixed steps)")
    if slow_step(v) > v.T:
        raise InputError(f"time step {slow_step(v)} s exceeds T = {v.T} s")
    if v.study == "dt":
        dts, levels = study_lists(v)
        if not dts or any(d <= 0 or d > v.T for d in dts):
            raise InputError(f"study_dts = {v.study_dts!r}: need 0 < Δt <= T")
        if any(not 0 <= m <= 4 for m in levels):
            raise InputError(f"study_meshes = {v.study_meshes!r}: levels 0..4")
        if v.mode != "steady":
            raise InputError("study=dt supports mode=steady only")
        if "bdf2" in study_schemes(v) and v.study_ref == "richardson":
            raise InputError("study_ref=richardson extrapolates a first-order "
                             "reference: use study_ref=fine with bdf2")
        r = v.study_ref_dt * (2 if v.study_ref == "richardson" else 1)
        if r > v.T or r >= min(dts):
            raise InputError("study_ref_dt must be below the study time steps")


def slow_step(v: Params) -> float:
    """Slow time step Δt (s): ``dt``, or cycles_per_step · 2 stroke / V in cyclic mode."""
    if v.mode == "cyclic" and v.cycles_per_step > 0:
        return v.cycles_per_step * 2 * v.stroke / v.V
    return v.dt


def n_elements(v: Params) -> int:
    """Elements per side of the structured mesh."""
    return 10 * 2 ** v.mesh


class Model(NamedTuple):
    """What :func:`build` assembles: the stepper of the pin's body, contact and wear.

    ``load``: the factor (0 → 1) of the traction q on the top face.
    """

    stepper: Stepper
    load: fem.Constant


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD, n: int | None = None,
          setup: Callable[[Body, Contact], object] | None = None,
          checkpoint: str | os.PathLike[str] | None = None) -> Model:
    """Body, contact, wear and slow-time stepper of the case; returns ``(stepper, load)``.

    ``load`` is the factor (Constant) of the top traction.  ``setup(body,
    contact)``, if given, runs before the problems are built (extra boundary
    conditions, e.g. in tests).  ``checkpoint``: directory of the per-step
    checkpoint.
    """
    n = n_elements(v) if n is None else n
    W, E, mu = v.W, v.E, v.friction
    cyclic = v.mode == "cyclic"
    if v.mesh_file:
        # (without ``cells``: the mesh, its facet tags and their names)
        msh, ft, names = cast("tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int]]",
                              read_user_mesh(v.mesh_file, comm, 2, tuple(NAMES)))
        W, h = place_user_pin(msh, ft, names)
    else:
        msh, ft = pin_body(W, v.H, v.R_tip if v.R_tip > 0 else math.inf, n, comm)
        names, h = NAMES, W / n
    lame_mu, lmbda = lame_parameters(E, v.nu)
    # the pin is at rest; in steady sliding the plane moves at V e_x (v_T = −V e_x, eq. 26)
    body = Body(msh, ft, names, "plane_strain", ("neo-hookean", {"mu": lame_mu,
                                                                 "lmbda": lmbda}),
                shape=True, aux=(E, 0.3), velocity=(0.0, 0.0) if mu > 0 else None)
    load = fem.Constant(msh, 1.0)
    body.add_traction("top", load * ufl.as_vector([0.0, -v.q]))
    body.add_dirichlet("sides", 0.0, component=0)
    body.add_shape_dirichlet("sides", 0)
    body.add_shape_dirichlet("top", 1)
    contact = Contact(body, "contact", rigid_plane(np.zeros(2), np.array([0.0, 1.0])),
                      rho_n=E / h, friction=mu,
                      slip="lagrangian" if cyclic else "eulerian", V_master=(v.V, 0.0))
    if setup is not None:
        setup(body, contact)
    k = (Law(wf.pressure_dependent_coefficient, k0=v.k, p_s=v.k_ps, m=v.k_m)
         if v.k_law == "pressure" else v.k)
    wear = Wear(contact, k=k, speed=v.V, law=v.law, k_grad=v.k_grad,
                scheme=v.scheme, averaged=cyclic)
    cycle = ReciprocatingCycle(contact, v.stroke, v.fast_steps, v.V) \
        if cyclic else None
    stepper = Stepper([body, contact, wear], wear, cycle=cycle, parameters=[load],
                      max_cuts=v.max_cuts, checkpoint=checkpoint, name="wear_pin")
    return Model(stepper, load)


def load_up(stepper: Stepper, load: fem.Constant, v: Params, verbose: bool = False) -> int:
    """Unworn contact under the full traction (load factor 0 → 1 by Continuation).

    Newton starts from the rigid translation δ₀ = a²/(2R) + qH/E of the pin (a
    the 2D Hertz half-width of the tip, ν = 0.3, at most W/2), so that the tip
    nodes start active; a failed solve halves the load increment.  Returns
    the Newton iterations spent.
    """
    R = v.R_tip
    a = min(hertz(v.q * v.W, R, v.E, 0.3, line=True).a, v.W / 2) if R else 0.0
    delta0 = (a * a / (2 * R) if a else 0.0) + v.q * v.H / v.E
    if v.mesh_file:   # a user's tip: its middle half starts in contact
        delta0 = user_pin_approach(stepper.wear.contact, v.q, v.E)
    stepper.wear.body.u.x.array.reshape(-1, 2)[:, 1] = -delta0
    # (DOLFINx types Constant.value's setter NDArray; it takes a float)
    load.value = 0.0  # type: ignore[assignment]
    control = Continuation(stepper.problem, ConstantParameter(load), verbose=verbose)
    control.march(1.0, steps=1, predictor=False)
    return int(sum(cast("list[int]", control.record)))   # (a Problem's: int per step)


def study_lists(v: Params) -> tuple[list[float], list[int]]:
    """``(dts, mesh levels)`` of ``study=dt`` parsed from the comma-separated strings."""
    dts = number_list(v.study_dts, "study_dts", allow_empty=True)
    levels = number_list(v.study_meshes, "study_meshes", int, True) or [v.mesh]
    return dts, levels


def study_schemes(v: Params) -> list[str]:
    """Schemes of ``study=dt`` (one-line error if unknown or none)."""
    schemes = [x.strip() for x in v.study_schemes.split(",") if x.strip()]
    if not schemes or any(x not in SCHEMES for x in schemes):
        raise InputError(f"study_schemes = {v.study_schemes!r}: a comma-separated "
                         "list of explicit, implicit, bdf2")
    return list(dict.fromkeys(schemes))


def progress_total(v: Params) -> int:
    """Return the steps the progress bar counts: slow steps to T."""
    return nominal_steps(v.T, slow_step(v))


def vtx_fields(stepper: Stepper) -> dict[str, list[fem.Function]]:
    """Fields for ParaView: displacement and shape change (bulk), contact multiplier."""
    return slow_time.wear_fields(stepper.wear)


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """Plot ``profiles.png``, ``wear.png`` (``study=dt``: ``error_vs_dt.png``, profiles)."""
    from ..plots.wear import plot_dt_study, plot_wear_pin

    if profile.get("study") == "dt":
        return plot_dt_study(profile, outdir)
    return plot_wear_pin(profile, outdir)


def run(v: Params, record: RunRecord | SubRecord, progress: tqdm | None = None,
        verbose: bool = False, n: int | None = None,
        setup: Callable[[Body, Contact], object] | None = None,
        checkpoint: str | os.PathLike[str] | None = None,
        resume: bool = False) -> Stepper | None:
    """Integrate the wear of the pin from t = 0 to T; record per-step histories.

    ``checkpoint``: directory of the per-step checkpoint (state and the
    histories so far); ``resume``: continue from it instead of t = 0.
    """
    if v.study == "dt":
        raise InputError("study=dt is a study of this case: tribofx.studies.wear_dt_study.run "
                         "runs it (as `tribofx run wear-pin --set study=dt` does)")
    stepper, load = build(v, n=n, setup=setup, checkpoint=checkpoint)
    stepper.verbose = verbose
    wear, contact = stepper.wear, stepper.wear.contact
    comm = wear.body.mesh.comm
    keys = ("time", "wear_volume", "max_wear_depth", "contact_radius",
            "newton_iterations", "wear_rate_integral", "dt", "error_estimate", "rejected")
    # the worn shape and the deformation at every step (ParaView time series)
    sr = slow_time.SlowTimeRecords(stepper, v, record, keys,
                 {"displacement": [wear.body.u, wear.body.w]}, resume)
    h = sr.history
    profiles, ptimes = h.setdefault("profiles", []), h.setdefault("ptimes", [])
    if stepper.cycle is None:
        record.data["newton_residuals"] = h.setdefault("newton_residuals", [])

    def log(t: float, its: int, dt: float, error: float | None = None,
            rejected: int = 0) -> None:
        area, _ = contact.measures()
        sr.log(its, (("time", t), ("dt", dt), ("wear_volume", wear.worn_volume()),
                     ("max_wear_depth", wear.max_depth()), ("contact_radius", area / 2),
                     ("newton_iterations", its),
                     ("wear_rate_integral", wear.wear_rate_integral()),
                     ("error_estimate", error), ("rejected", rejected)))
        s = wear.gather_shape()
        if comm.rank == 0:
            profiles.append(s["X_worn"].tolist())
            ptimes.append(t)

    def on_step(st: Stepper, rep: StepReport) -> None:
        log(st.t, rep.iterations, rep.dt, rep.error, rep.rejected)
        if st.cycle is None:
            record.data["newton_residuals"].append(
                [float(x) for x in rep.reports[-1].residuals])

    if not resume:
        log(0.0, load_up(stepper, load, v, verbose) + stepper.start(), 0.0)
    with sr.closing(report=lambda: _report(stepper, v, record, sr.hist, profiles,
                                               ptimes)):
        stepper.run(v.T, slow_time.step_controller(v, slow_step(v)),
                    on_step=sr.written(on_step), progress=progress)
    return stepper


def _report(stepper: Stepper, v: Params, record: RunRecord | SubRecord,
            hist: Mapping[str, list[Any]], profiles: list[list[list[float]]],
            ptimes: list[float]) -> None:
    units = {"time": "s", "wear_volume": "mm^3/mm", "max_wear_depth": "mm",
             "contact_radius": "mm (half-width)", "newton_iterations": "-",
             "wear_rate_integral": "mm^3/(mm*s)", "dt": "s",
             "error_estimate": "mm (per step, error control)", "rejected": "-"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    record.result("accepted_steps", len(hist["time"]) - 1, "-")
    record.result("rejected_steps", int(sum(hist["rejected"])), "-")
    d = stepper.wear.gather_shape()
    if d is not None:
        record.result("final_profile", d["X_worn"].tolist(), "mm (worn configuration)")
        record.result("final_profile_deformed", d["x"].tolist(), "mm (current)")
        record.result("final_pressure", d["p"].tolist(), "MPa")
        record.profile = {**hist, "profiles": profiles, "times": ptimes,
                          "scheme": v.scheme, "dt": slow_step(v)}
