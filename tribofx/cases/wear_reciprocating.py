"""Reciprocating pin-on-flat, both bodies elastic and worn (§5.1, Fig. 5): ``wear-reciprocating``.

An elastic plane-strain pin (width W, height H, rounded tip of radius R_tip) is
pressed by a constant normal force F (a uniform traction F/W on its top face;
its sides x = ±W/2 held laterally) onto an elastic block (length L, depth D,
top y = 0) whose bottom is moved back and forth along x with amplitude A at
speed V.  Both are neo-Hookean; Coulomb friction μ.  The pin's tip is the
slave surface, the block's top the master
(:class:`~tribofx.interfaces.TwoBodyContact`: every slave node is projected on
the current block surface).

Both surfaces wear (Archard in the dissipation form, eq. 14, nominal
coefficients K_pin and K_block): a :class:`~tribofx.interfaces.Wear` on each
side, the pin's driven by its own dissipation K⁽¹⁾ D⁽¹⁾ (eq. 17), the block's
by K⁽²⁾ D⁽¹⁾ carried to the block nodes the pin rubbed against (eq. 18); both
shape fields evolve (finite shape changes of both bodies, on their initial
meshes).  Time-scale separation (eqs. 21–23): per slow step one fast loading
cycle at the fixed worn shapes — the contact memory erased, the block at −A, a
run-in to the centre, then +A, −2A, +A — accumulates the wear increment of
every node; the average rate over the cycle (Δτ = 4A/V) drives the shape step,
explicit (θ = 0, as in the chapter) or implicit (θ = 1 by a Picard iteration of
cycles); :class:`~tribofx.stepper.Stepper`.  A slow step of Δt stands for
Δt/Δτ cycles; the run covers ``cycles`` cycles, T = cycles·Δτ.

Data: the chapter leaves them to Lengiewicz & Stupkiewicz (2012); chosen here
so that both bodies deform finitely and both wear visibly: W = H = 2 mm,
R_tip = 2 mm (a half-round tip), block 6 × 1.5 mm, E_pin = 20 MPa, E_block =
10 MPa (rubber-like: Hertz half-width 0.59 mm and peak pressure 1.1 MPa, so
strains of about 10 %), ν = 0.3, μ = 0.3, A = 0.5 mm, V = 10 mm/s, F = 1 N/mm,
K_pin = 10⁻⁴ and K_block = 5·10⁻⁵ mm³/(N·mm), 2000 cycles: gross sliding would
dissipate μF·4A = 0.6 N·mm/mm per cycle (the stick phases after each reversal
take about 13 % off), so the pin loses about 0.1 mm² per mm, a flat of about
1.5 mm on its tip, and the block half of that, a groove along the stroke.

Your own pin (``mesh_file``): a 2D gmsh ``.msh`` whose physical groups are the
case's own (:data:`tribofx.meshes.pin.NAMES`): ``contact`` (the tip, the slave
surface), ``top`` (loaded) and ``sides`` (held laterally), read and checked by
:func:`tribofx.meshes.user.read_user_mesh`.  It is moved as
:func:`tribofx.cases.user_pin.place_user_pin` moves the pin of ``wear-pin``
(its lowest tip point to y = 0, the block's top) and its x extent centred on
x = 0 (the centre of the stroke); it replaces ``W``, ``H``, ``R_tip`` and the
pin's mesh.  What the case takes from W, R_tip and n it then takes from the
mesh: W is the mesh's x extent (the stroke check L ≥ W + 2A + 1 mm), the top
traction is F/ℓ with ℓ the length of ``top`` (so that the pin carries F; ℓ = W
for the case's pin), the element size h = W/n is the mean length of the tip
facets (ρ_N = min(E_pin, E_block)/h and the block's element size 4h/3:
``mesh`` then refines nothing), and Newton's start on load-up is the approach
of :func:`~tribofx.cases.user_pin.user_pin_approach` (the tip's height at
|x| = W/4, so that its middle half starts in contact, plus the pin's
compression F H/(ℓ E_pin)) instead of the Hertz approach of R_tip.  The checks
R_tip ≥ W/2 and tip height < H/2 are those of the built circular tip and do
not apply.  ``pin_width``, ``pin_height``, ``pin_top_length`` and
``contact_element_size`` report what was used (the built pin's W, H, W, W/n
without ``mesh_file``).

Results per slow step and outputs: :mod:`tribofx.cases.wear_reciprocating`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeAlias, cast

import numpy as np
import ufl
from dolfinx import fem
from mpi4py import MPI

from ..body import Body
from ..continuation import ConstantParameter, Continuation
from ..forms.hyperelastic import lame_parameters
from ..interfaces import TwoBodyContact, Wear
from ..meshes.block import NAMES as BLOCK_NAMES
from ..meshes.block import block_mesh
from ..meshes.pin import NAMES as PIN_NAMES
from ..meshes.pin import pin_body, tip_height
from ..meshes.user import read_user_mesh
from ..params import InputError, param
from ..references import hertz
from ..stepper import ReciprocatingCycle, Stepper, nominal_steps
from . import slow_time
from .slow_time import SchemeParams, check_scheme, scheme_param
from .user_pin import place_user_pin, user_pin_approach

if TYPE_CHECKING:
    import os
    from collections.abc import Mapping, Sequence
    from pathlib import Path

    import numpy.typing as npt
    from dolfinx import mesh as dmesh
    from tqdm import tqdm

    from ..output import RunRecord

    #: a body's owned cells on rank 0 (:func:`cell_coordinates`): X̂, w and u at their
    #: vertices, each (n, 3, 2)
    Cells: TypeAlias = tuple[npt.NDArray[np.float64], ...]
    #: a :func:`snapshot`: [pin, block] cells at −A, at the centre and at +A (None off rank 0)
    Shot: TypeAlias = list[list[Cells | None]]

__all__ = ["Model", "Params", "build", "cell_coordinates", "check_stroke", "doc", "load_up", "name",
           "period", "plot", "progress_total", "resumable", "run", "snapshot", "validate",
           "vtx_fields"]


def cell_coordinates(body: Body) -> Cells | None:
    """Owned cells of ``body`` as (n, 3, 2) arrays of X̂, w and u at their vertices, on rank 0.

    For pictures of the initial (X̂), worn (X̂ + w) and deformed (X̂ + w + u)
    configurations; None on the other ranks.
    """
    msh = body.mesh
    n = msh.topology.index_map(msh.topology.dim).size_local
    geo = msh.geometry.dofmaps[0][:n]
    dofs = body.V.dofmap.list[:n, :3]
    X = msh.geometry.x[geo, :2]
    u = body.u.x.array.reshape(-1, 2)[dofs]
    assert body.w is not None   # a worn body (shape=True)
    w = body.w.x.array.reshape(-1, 2)[dofs]
    parts = msh.comm.gather((X, w, u), root=0)
    if msh.comm.rank != 0:
        return None
    assert parts is not None    # gathered on rank 0
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(3))


def _jsonable(shot: Shot | None) -> list[list[list[Any]]] | None:
    """Return a :meth:`snapshot` as nested lists (None off rank 0)."""
    if shot is None or any(body is None for part in shot for body in part):
        return None
    # (no body is None here)
    return [[[np.asarray(a).tolist() for a in cast("Cells", body)] for body in part]
            for part in shot]


def _arrays(shot: Sequence[Sequence[Sequence[Any]]] | None) -> Shot | None:
    """Return the arrays of a :func:`_jsonable` snapshot."""
    if shot is None:
        return None
    return [[tuple(np.asarray(a) for a in body) for body in part] for part in shot]


def _centre_on_axis(msh: dmesh.Mesh) -> None:
    """Translate a user's pin along x so that its x extent is centred on x = 0.

    The case's own pin is symmetric about x = 0, the centre of the block and of
    the stroke; a user's pin is put there by the midpoint of its extent (its
    sides, held laterally, at x = ±W/2).
    """
    comm, x = msh.comm, msh.geometry.x
    lo = comm.allreduce(float(np.min(x[:, 0], initial=np.inf)), op=MPI.MIN)
    hi = comm.allreduce(float(np.max(x[:, 0], initial=-np.inf)), op=MPI.MAX)
    x[:, 0] -= 0.5 * (lo + hi)


name = "wear-reciprocating"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "elastic pin on an elastic block, reciprocating sliding, both worn (§5.1, Fig. 5)"


@dataclass(frozen=True)
class Params(SchemeParams):
    """The parameters of ``wear-reciprocating`` (``--set KEY=VALUE``)."""

    scheme: str = scheme_param("explicit", "; implicit ones with the Picard iteration of cycles, "
        "tol on the cycle-averaged shapes")
    E_pin: float = param(20.0, "MPa", "Young's modulus of the pin", lower=0.0)
    E_block: float = param(10.0, "MPa", "Young's modulus of the block", lower=0.0)
    nu: float = param(0.3, "-", "Poisson's ratio of both bodies", lower=-1.0, upper=0.5)
    friction: float = param(0.3, "-", "Coulomb coefficient μ", lower=0.0)
    K_pin: float = param(
        1e-4, "mm^3/(N*mm)",
        "nominal wear coefficient of the pin (eq. 14)",
        lower=0.0)
    K_block: float = param(
        5e-5, "mm^3/(N*mm)",
        "nominal wear coefficient of the block (eq. 14)",
        lower=0.0, closed=True)
    A: float = param(0.5, "mm", "amplitude of the reciprocating motion (stroke 2A)", lower=0.0)
    V: float = param(10.0, "mm/s", "sliding speed", lower=0.0)
    F: float = param(1.0, "N/mm", "normal force on the pin per unit thickness", lower=0.0)
    cycles: float = param(2000.0, "-", "loading cycles of the run (T = cycles·4A/V)", lower=0.0)
    dt: float = param(
        40.0, "s",
        "slow time step Δt (Δt·V/(4A) cycles per step; "
        "with tol: the first step)",
        lower=0.0)
    W: float = param(2.0, "mm", "pin width", lower=0.0)
    H: float = param(2.0, "mm", "pin height", lower=0.0)
    R_tip: float = param(2.0, "mm", "tip radius", lower=0.0)
    L: float = param(6.0, "mm", "block length", lower=0.0)
    D: float = param(1.5, "mm", "block depth", lower=0.0)
    mesh: int = param(
        1, "-",
        "refinement: pin n × n, n = 10·2^mesh; block at 4/3 the size",
        lower=0, upper=4, closed=True)
    fast_steps: int = param(
        16, "-",
        "fast sub-steps per cycle (multiple of 4)",
        lower=4, upper=100000, closed=True)
    max_cuts: int = param(4, "-", "step halvings allowed per step", lower=0, upper=20, closed=True)
    mesh_file: str = param(
        "", "-",
        "your own pin: a 2D gmsh .msh with physical groups contact (the tip), top "
        "(loaded by F: traction F/l, l its length) and sides (held laterally); its "
        "lowest tip point moved to y = 0 and its x extent centred on x = 0; replaces "
        "W (its x extent: L >= W + 2A + 1), H, R_tip and the pin's mesh (h = mean tip "
        "facet length: rho_N = min(E)/h, block elements 4h/3)")


def validate(v: Params) -> None:
    """Reject a stroke off the block, a tip lower than the pin and a step above T.

    With ``mesh_file`` the pin's width is known only once the mesh is read:
    :meth:`build` checks the stroke then (:meth:`check_stroke`); the tip
    checks are those of the built circular tip.
    """
    if not v.mesh_file:
        if v.R_tip < v.W / 2:
            raise InputError(f"R_tip = {v.R_tip} mm must be >= W/2 = {v.W / 2} mm")
        if tip_height(v.W / 2, v.R_tip) >= 0.5 * v.H:
            raise InputError("the rounded tip must be lower than half the pin height")
        check_stroke(v, v.W)
    check_scheme(v)
    if v.fast_steps % 4:
        raise InputError(f"fast_steps = {v.fast_steps} must be a multiple of 4")
    if v.dt > period(v) * v.cycles:
        raise InputError(f"time step {v.dt} s exceeds T = "
                         f"{period(v) * v.cycles} s")


def check_stroke(v: Params, W: float) -> None:
    """Reject a block too short for a pin of width ``W`` (mm) and the stroke 2A.

    The pin must stay on the block with 0.5 mm to spare at either end of the
    stroke: L ≥ W + 2A + 1 mm.
    """
    if v.L < W + 2 * v.A + 1.0:
        where = f" (W = {W:.6g} mm: the width of the pin in {v.mesh_file!r})" \
            if v.mesh_file else ""
        raise InputError(f"block length L = {v.L} mm must exceed W + 2A + 1 = "
                         f"{W + 2 * v.A + 1.0:.6g} mm{where}")


def period(v: Params) -> float:
    """Δτ of one cycle, 4A/V (s)."""
    return 4 * v.A / v.V


@dataclass
class Model:
    """What :func:`build` assembles: pin and block, their contact, each one's wear, the stepper.

    ``load``: the factor (0 → 1) of the force F on the pin's top; ``motion``: the
    block's prescribed displacement (a Constant); ``cycle``: the fast reciprocating
    cycle; ``W``, ``H``: the pin's width and height, ``top_length`` its loaded
    length, ``h`` the contact element size (mm).
    """

    pin: Body
    block: Body
    contact: TwoBodyContact
    wear_pin: Wear
    wear_block: Wear
    stepper: Stepper
    load: fem.Constant
    motion: fem.Constant
    cycle: ReciprocatingCycle
    W: float
    H: float
    top_length: float
    h: float


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD,
          checkpoint: str | os.PathLike[str] | None = None) -> Model:
    """Pin, block, contact, both wear interfaces, the cycle and the stepper: a :class:`Model`.

    The model also holds the pin's geometry as used: ``W`` (width), ``H``
    (height above the lowest tip point), ``top_length`` (ℓ of the traction
    F/ℓ) and ``h`` (tip element size); from the mesh with ``mesh_file``.
    """
    if v.mesh_file:
        # (without ``cells``: the mesh, its facet tags and their names)
        msh, ft, names = cast("tuple[dmesh.Mesh, dmesh.MeshTags, dict[str, int]]",
                              read_user_mesh(v.mesh_file, comm, 2, tuple(PIN_NAMES)))
        W, h = place_user_pin(msh, ft, names)
        check_stroke(v, W)
        _centre_on_axis(msh)
        H = comm.allreduce(float(np.max(msh.geometry.x[:, 1], initial=-np.inf)),
                           op=MPI.MAX)
    else:
        n = 10 * 2 ** v.mesh
        W, H, h = v.W, v.H, v.W / n
        msh, ft = pin_body(W, H, v.R_tip, n, comm)
        names = PIN_NAMES
    mu, lmbda = lame_parameters(v.E_pin, v.nu)
    pin = Body(msh, ft, names, "plane_strain", ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
               shape=True, aux=(v.E_pin, 0.3), name="pin")
    # the top's length: the traction F/ℓ loads the pin with F whatever its top
    top = comm.allreduce(fem.assemble_scalar(fem.form(
        fem.Constant(msh, 1.0) * pin.ds(pin.tag("top")))), op=MPI.SUM) \
        if v.mesh_file else W
    load = fem.Constant(msh, 1.0)
    pin.add_traction("top", load * ufl.as_vector([0.0, -v.F / top]))
    pin.add_dirichlet("sides", 0.0, component=0)
    pin.add_shape_dirichlet("sides", 0)
    pin.add_shape_dirichlet("top", 1)
    hb = 4 * h / 3                       # the slave (pin) is the finer surface
    bmsh, bft = block_mesh(comm, (-v.L / 2, -v.D), (v.L / 2, 0.0),
                           round(v.L / hb), max(2, round(v.D / hb)))
    mu, lmbda = lame_parameters(v.E_block, v.nu)
    block = Body(bmsh, bft, BLOCK_NAMES, "plane_strain",
                 ("neo-hookean", {"mu": mu, "lmbda": lmbda}), shape=True,
                 aux=(v.E_block, 0.3), name="block")
    motion = block.add_dirichlet("bottom", np.zeros(2))
    for name, c in (("bottom", 0), ("bottom", 1), ("sides", 0)):
        block.add_shape_dirichlet(name, c)
    contact = TwoBodyContact(pin, "contact", block, "top",
                             rho_n=min(v.E_pin, v.E_block) / h, friction=v.friction)
    mu_f = v.friction
    wear_pin = Wear(contact.wear_surface("slave"), k=v.K_pin * mu_f,
                    scheme=v.scheme, averaged=True, name="wear_pin")
    wear_block = Wear(contact.wear_surface("master"), k=v.K_block * mu_f,
                      scheme=v.scheme, averaged=True, name="wear_block")

    def drive(position: float) -> None:
        """Move the block's bottom to ``position``; the block translated as predictor."""
        block.u.x.array.reshape(-1, 2)[:, 0] += position - float(motion.value[0])
        motion.value[0] = position

    cycle = ReciprocatingCycle(contact, 2 * v.A, v.fast_steps, v.V, drive=drive,
                               force=lambda: block.reaction("bottom", 0))
    stepper = Stepper([pin, block, contact, wear_pin, wear_block], [wear_pin, wear_block],
                      cycle=cycle, parameters=[load, motion], max_cuts=v.max_cuts,
                      checkpoint=checkpoint, name="wear_reciprocating",
                      problem_kw={"max_it": 40})
    return Model(pin, block, contact, wear_pin, wear_block, stepper, load, motion, cycle, W, H,
                 top, h)


def progress_total(v: Params) -> int:
    """Return the slow steps the progress bar counts: nominal steps to T = cycles·Δτ."""
    return nominal_steps(v.cycles * period(v), v.dt)


def load_up(run: Model, v: Params, verbose: bool = False) -> int:
    """Press the pin onto the block under F (load factor 0 → 1); Newton iterations.

    Newton starts from the pin translated down by the Hertz approach a²/(2R)
    of the tip (2D Hertz, both moduli) plus its compression F H/(W E_pin); a
    user's pin (``mesh_file``) by its tip height at |x| = W/4 plus F H/(ℓ E_pin)
    (:func:`tribofx.cases.user_pin.user_pin_approach` with the pin's
    traction q = F/ℓ and modulus).
    """
    if v.mesh_file:
        delta0 = user_pin_approach(run.wear_pin.contact, v.F / run.top_length, v.E_pin)
    else:
        a = min(hertz(v.F, v.R_tip, v.E_pin, v.nu, math.inf, v.E_block,
                      v.nu, line=True).a, v.W / 2)
        delta0 = a * a / (2 * v.R_tip) + v.F * v.H / (v.W * v.E_pin)
    run.pin.u.x.array.reshape(-1, 2)[:, 1] = -delta0
    # (DOLFINx types Constant.value's setter NDArray; it takes a float)
    run.load.value = 0.0  # type: ignore[assignment]
    control = Continuation(run.stepper.problem, ConstantParameter(run.load),
                           verbose=verbose)
    control.march(1.0, steps=2, predictor=False)
    return int(sum(cast("list[int]", control.record)))   # (a Problem's: int per step)


def snapshot(run: Model) -> Shot:
    """Cells of both bodies (X̂, w, u) at −A, at the centre and at +A of a cycle (rank 0).

    Runs the start of a cycle at the current shapes: memory erased, the
    block at −A (a), the run-in to the centre (b), the first quarter to +A
    (c); then restarts, so the state is that of a cycle start again.
    """
    st, cyc = run.stepper, run.cycle
    P = st.problem
    shots: Shot = []
    cyc.start()
    P.commit()
    P.solve_by_homotopy()
    P.commit()
    shots.append([cell_coordinates(run.pin), cell_coordinates(run.block)])
    for pos in cyc.run_in:
        cyc.move(pos)
        P.solve_by_homotopy()
        P.commit()
    shots.append([cell_coordinates(run.pin), cell_coordinates(run.block)])
    for pos in cyc.positions[:cyc.fast_steps // 4]:
        cyc.move(pos)
        P.solve_by_homotopy()
        P.commit()
    shots.append([cell_coordinates(run.pin), cell_coordinates(run.block)])
    st.restart()
    return shots


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        checkpoint: str | os.PathLike[str] | None = None, resume: bool = False) -> Model:
    """Load, then integrate the wear of both bodies over ``cycles``; per-step histories.

    ``checkpoint``: directory of the per-step checkpoint (state and histories);
    ``resume``: continue from it (:mod:`tribofx.restart`).
    """
    run = build(v, checkpoint=checkpoint)
    st, contact, cycle = run.stepper, run.contact, run.cycle
    wp, wb = run.wear_pin, run.wear_block
    st.verbose = verbose
    for key, val, unit in (("pin_width", run.W, "mm"), ("pin_height", run.H, "mm"),
                           ("pin_top_length", run.top_length, "mm"),
                           ("contact_element_size", run.h, "mm")):
        record.result(key, val, unit)
    pin = run.pin
    # the pin's vertical equilibrium: Σ of its momentum rows along y (each below
    # atol_u at a solved state) is F − (contact force along y)
    record.result("normal_force_bound", pin.V.dofmap.index_map.size_global * 2
                  * pin.tolerances()[pin.u].atol, "N/mm")
    tau = period(v)
    # the worn shapes and the deformation at every slow step (ParaView time series)
    sr = slow_time.SlowTimeRecords(st, v, record, (
        "time", "cycles_done", "worn_area_pin", "worn_area_block", "dissipated_energy",
        "cycle_dissipation", "drive_work", "drive_work_bound", "friction_force_ratio",
        "rate_integral_pin", "rate_integral_block", "normal_force", "newton_iterations",
        "picard_iterations", "dt", "error_estimate", "rejected"), vtx_fields(run),
        resume)
    h, hist = sr.history, sr.hist
    energy = [hist["dissipated_energy"][-1] if resume else 0.0]
    w_ref = contact.surface.nodal(ufl.TestFunction(contact.Q) * contact.dsc)

    def log(t: float, dt: float, its: int, picard: int = 0, error: float | None = None,
            rejected: int = 0) -> None:
        comm = contact.slave.mesh.comm
        if st.last_increments is not None:   # dissipation of the step's (last) cycle
            d_pin = st.last_increments[0]
            n = contact.Q.dofmap.index_map.size_local
            cyc_d = comm.allreduce(float(d_pin[:n] @ w_ref[:n]), op=MPI.SUM) / v.K_pin
            energy[0] += cyc_d * dt / tau
        else:
            cyc_d = None
        sr.log(its, (("time", t), ("cycles_done", t / tau),
                     ("worn_area_pin", wp.worn_volume()),
                     ("worn_area_block", wb.worn_volume()),
                     ("dissipated_energy", energy[0]), ("cycle_dissipation", cyc_d),
                     ("drive_work", cycle.work), ("drive_work_bound", cycle.work_bound),
                     ("friction_force_ratio", cycle.sliding_force_ratio(v.F)),
                     ("rate_integral_pin", wp.wear_rate_integral()),
                     ("rate_integral_block", wb.wear_rate_integral()),
                     ("normal_force", float(contact.forces()[0][1])),
                     ("newton_iterations", its), ("picard_iterations", picard),
                     ("dt", dt), ("error_estimate", error), ("rejected", rejected)))

    if not resume:
        log(0.0, 0.0, load_up(run, v, verbose))
        h["initial_shot"] = _jsonable(snapshot(run))
    shots: dict[str, Shot | None] = {"initial": _arrays(h["initial_shot"])}

    def report() -> None:
        _report(run, record, hist, shots)
        if record.profile is not None:
            half = 0.5 * v.L + v.A + 0.1
            record.profile["view"] = ((-half, half), (-v.D - 0.1, 0.6 * run.H))

    with sr.closing(report=report, model=run):
        st.run(v.cycles * tau, slow_time.step_controller(v, v.dt), progress=progress,
               on_step=sr.written(lambda s, rep: log(s.t, rep.dt, rep.iterations, rep.picard,
                                                     rep.error, rep.rejected)))
        shots["worn"] = snapshot(run)
    return run


def _report(run: Model, record: RunRecord, hist: Mapping[str, list[Any]],
            shots: Mapping[str, Shot | None]) -> None:
    units = {"time": "s", "cycles_done": "-", "worn_area_pin": "mm^2/mm",
             "worn_area_block": "mm^2/mm", "dissipated_energy": "N*mm/mm",
             "cycle_dissipation": "N*mm/mm", "drive_work": "N*mm/mm",
             "drive_work_bound": "N*mm/mm", "friction_force_ratio": "-",
             "rate_integral_pin": "mm^2/(mm*s)", "rate_integral_block": "mm^2/(mm*s)",
             "normal_force": "N/mm", "newton_iterations": "-", "picard_iterations": "-",
             "dt": "s", "error_estimate": "mm (per step, error control)",
             "rejected": "-"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    record.result("accepted_steps", len(hist["time"]) - 1, "-")
    record.result("rejected_steps", int(sum(hist["rejected"])), "-")
    prof: dict[str, dict[str, npt.NDArray[Any]]] = {}
    for key, wear in (("wear_pin", run.wear_pin), ("wear_block", run.wear_block)):
        d = wear.gather_shape()
        if d is not None:
            prof[key] = {"X_hat": d["X_hat"], "X_worn": d["X_worn"], "x": d["x"],
                         "depth": d["depth"]}
            record.result(f"final_profile_{key[5:]}", d["X_worn"].tolist(),
                          "mm (worn configuration)")
            record.result(f"final_depth_{key[5:]}", d["depth"].tolist(), "mm")
    if MPI.COMM_WORLD.rank == 0:
        record.profile = {**hist, **prof, "shots": shots}


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacement and shape change of both bodies (one file per mesh)."""
    assert run.pin.w is not None and run.block.w is not None   # worn bodies (shape=True)
    return {"pin": [run.pin.u, run.pin.w], "block": [run.block.u, run.block.w]}


def plot(profile: Mapping[str, Any], outdir: Path) -> None:
    """``fig5.png`` (configurations, both bodies) and ``wear.png`` (histories, profiles)."""
    from ..plots.two_body import plot_reciprocating

    plot_reciprocating(profile, outdir)
