"""Running-in of a soft cylinder under mixed lubrication: the asperities wear it.

``wear-lubricated`` — the cylinder of ``stribeck`` (neo-Hookean, plane strain,
radius R, held at its flat face) under the load W (N/mm) on the rough rigid
plane sliding at V (mm/s), in the mixed regime: the average-flow film and the
Greenwood–Tripp asperities share W.  The asperities, not the film, wear the
cylinder by Archard's law,

    Ẇ j_w = k p_a j ‖v_s‖        (k in mm³/(N·mm), p_a = K E* F_{5/2}(h/σ)),

(:func:`tribofx.forms.mixed.asperity_wear_load`), and the worn shape changes the
film: the finite shape update (28) of the core (:class:`tribofx.interfaces.Wear`
on the film, the ALE shape field of the body), monolithic with the film and the
body (``scheme=implicit``: θ = 1; ``bdf2``: second order, ``tol`` its error
control; ``explicit``: θ = 0).  W is held at every step by the plane's approach
(a secant on log W, :class:`tribofx.hold.Hold`).

The run: W is reached at ``U_start`` (a full film, the load march of
``stribeck``), the speed is marched down to V, then the slow time runs from 0
to T in steps dt.  As the cylinder conforms, the asperity load falls and the
film's share of W grows: the film builds up.

Results per step: ``time``, ``wear_volume`` (worn area per unit length, mm²),
``max_wear_depth``, ``asperity_load``, ``film_load_fraction``,
``friction_coefficient``, ``h_central``, ``h_min``, ``wear_rate_integral``
(∫ Ẇ dS, mm²/s), ``newton_iterations``; the worn profiles; the final film
(h, p, p_a).  Units: mm, N, s, MPa.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, cast

from mpi4py import MPI

from ..continuation import ConstantParameter, Continuation
from ..hold import Hold
from ..interfaces import Wear
from ..params import InputError, param
from ..stepper import Stepper, nominal_steps
from . import rough_contact, slow_time

if TYPE_CHECKING:
    import os
    from pathlib import Path

    from dolfinx import fem
    from tqdm import tqdm

    from ..obstacles import AnalyticObstacle
    from ..output import RunRecord

__all__ = ["Model", "Params", "build", "doc", "name", "plot", "progress_total", "report",
           "resumable", "run", "validate", "vtx_fields"]



name = "wear-lubricated"
#: writes a checkpoint every step: `--resume` continues an interrupted run
resumable = True
doc = "running-in of a soft cylinder worn by its asperity contact under mixed lubrication"


@dataclass(frozen=True)
class Params(rough_contact.RoughContactParams, slow_time.SchemeParams):
    """The parameters of ``wear-lubricated`` (``--set KEY=VALUE``)."""

    V: float = param(1.0, "mm/s", "sliding speed of the plane (mixed regime)", lower=0.0)
    U_start: float = param(1000.0, "mm/s", "speed at which W is reached (full film)", lower=0.0)
    k: float = param(
        1e-5, "mm^3/(N*mm)",
        "Archard coefficient (1e-5 mm³/(N·mm) = 1e-2 mm³/(N·m): an elastomer "
        "on a rough counterface)",
        lower=0.0)
    T: float = param(7200.0, "s", "slow time (sliding distance V·T)", lower=0.0)
    dt: float = param(720.0, "s", "slow-time step", lower=0.0)
    max_cuts: int = param(6, "-", "step halvings allowed per step", lower=0, upper=20, closed=True)


def validate(v: Params) -> None:
    """Bad input: a one-line error."""
    if v.V >= v.U_start:
        raise InputError("V must be below U_start (W is reached at U_start)")
    slow_time.check_scheme(v)
    rough_contact.check(v, "cylinder", [v.U_start, v.V])


def progress_total(v: Params) -> int:
    """Return the number of slow steps."""
    return nominal_steps(v.T, v.dt)


@dataclass
class Model(rough_contact.Model):
    """The rough cylinder of :class:`tribofx.cases.rough_contact.Model` with its wear.

    ``stepper``: the slow time (its monolithic problem is ``problem``); ``track``:
    (t, plane position) of the accepted steps.
    """

    wear: Wear
    stepper: Stepper
    track: list


def build(v: Params, comm: MPI.Comm = MPI.COMM_WORLD,
          checkpoint: str | os.PathLike[str] | None = None) -> Model:
    """Cylinder with a shape field, rough film, wear, stepper and the load control.

    Returns the :class:`Model`; ``problem`` is the stepper's monolithic Problem.
    """
    run = rough_contact.build(v, "cylinder", v.U_start, comm, shape=True)
    film = run.film
    wear = Wear(film, k=v.k, speed=v.V, scheme=v.scheme)
    stepper = Stepper([run.body, film, wear], wear, max_cuts=v.max_cuts,
                      checkpoint=checkpoint, name="wear_lubricated",
                      problem_kw={"max_it": 30})
    offset = cast("AnalyticObstacle", film.counterpart).offset   # the rigid plane's
    # (t, plane position) of the accepted steps (appended by ``run``)
    track: list[tuple[float, float]] = []

    def predictor(dt: float) -> float:
        # the plane follows the worn surface: its last rate (none before two steps;
        # the mean worn depth k F_a V Δt/(2a) overshoots the plane's rise about 2×
        # as the film takes load back, and a trial 0.3σ off may not converge)
        if len(track) < 2:
            return float(offset.value[1])
        (t0, y0), (t1, y1) = track[-2:]
        return y1 + (y1 - y0) * dt / (t1 - t0)

    search = Continuation(stepper.problem, ConstantParameter(offset, 1),
                          response=lambda: math.log(max(float(film.force()[1]), 1e-300)),
                          rtol=1e-7, max_trials=30)
    stepper.hold = Hold(search, math.log(v.W), step_guess=predictor,
                        step_slope=lambda dt: 1.0 / max(film.min_film(), v.sigma))
    return Model(**{**vars(run), "problem": stepper.problem}, wear=wear, stepper=stepper,
                 track=track)


def run(v: Params, record: RunRecord, progress: tqdm | None = None, verbose: bool = False,
        comm: MPI.Comm = MPI.COMM_WORLD, checkpoint: str | os.PathLike[str] | None = None,
        resume: bool = False) -> Model:
    """Reach W and V, then integrate the wear from t = 0 (or the checkpoint) to T."""
    run = build(v, comm, checkpoint)
    stepper, wear, film = run.stepper, run.wear, run.film
    assert stepper.hold is not None   # build holds the load
    stepper.verbose = stepper.hold.search.verbose = verbose
    keys = ("time", "dt", "wear_volume", "max_wear_depth", "asperity_load",
            "film_load_fraction", "friction_coefficient", "h_central", "h_min",
            "wear_rate_integral", "newton_iterations", "error_estimate", "rejected")
    sr = slow_time.SlowTimeRecords(stepper, v, record, keys, vtx_fields(run), resume)
    state = sr.history.setdefault("state", {"profiles": [], "times": []})

    def log(t: float, its: int, dt: float, error: float | None = None,
            rejected: int = 0) -> None:
        m = rough_contact.measures(run, v)
        sr.log(its, {"time": t, "dt": dt, "wear_volume": wear.worn_volume(),
                     "max_wear_depth": wear.max_depth(),
                     **{k: m[k] for k in ("asperity_load", "film_load_fraction",
                                          "friction_coefficient", "h_central", "h_min")},
                     "wear_rate_integral": wear.wear_rate_integral(),
                     "newton_iterations": its, "error_estimate": error,
                     "rejected": rejected})
        plane = cast("AnalyticObstacle", film.counterpart)   # the rigid plane
        run.track.append((t, float(plane.offset.value[1])))
        d = wear.gather_shape()
        if d is not None:
            state["profiles"].append(d["X_worn"].tolist())
            state["times"].append(t)

    if resume:   # the state is the checkpoint's; the speed is V
        rough_contact.set_speed(run, v.V)
    else:
        its = []
        rough_contact.load_and_slow(run, v, [v.U_start, v.V], verbose,
                                   lambda U, n: its.append(n))
        log(0.0, sum(its) + stepper.start(), 0.0)
    with sr.closing(report=lambda: report(run, v, record, sr.hist, state), model=run):
        stepper.run(v.T, slow_time.step_controller(v, v.dt), progress=progress,
                    on_step=sr.written(lambda st, rep: log(st.t, rep.iterations, rep.dt,
                                                           rep.error, rep.rejected)))
    return run


def report(run: Model, v: Params, record: RunRecord, hist: dict[str, list[Any]],
           state: dict[str, list[Any]]) -> None:
    """Per-step lists, the final film (h, p, p_a) and the worn profiles."""
    units = {"time": "s", "dt": "s", "wear_volume": "mm^2/mm", "max_wear_depth": "mm",
             "asperity_load": "N/mm", "film_load_fraction": "-",
             "friction_coefficient": "-", "h_central": "mm", "h_min": "mm",
             "wear_rate_integral": "mm^2/(mm*s)", "newton_iterations": "-",
             "error_estimate": "mm", "rejected": "-"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    record.result("accepted_steps", max(len(hist["time"]) - 1, 0), "-")
    if state["profiles"]:
        record.result("worn_profiles", {"time": state["times"],
                                        "X_worn": state["profiles"]},
                      "s, mm (worn configuration, nodes of the film face by X̂₀)")
    prof = run.film.profile()
    if prof is not None:
        film = {"x": prof["X"][:, 0].tolist(),
                **{k: prof[k].tolist() for k in ("h", "p", "p_a")}}
        record.result("final_film", film, "mm, MPa")
        record.profile = {**hist, **state, "film": film}


def vtx_fields(run: Model) -> dict[str, list[fem.Function]]:
    """Displacement and shape change of the cylinder."""
    assert run.body.w is not None   # built with a shape field (build)
    return {"displacement": [run.body.u, run.body.w]}


def plot(profile: dict[str, Any], outdir: Path) -> None:
    """``running_in.png``: worn profiles, loads and friction against time."""
    from ..plots.film import plot_running_in

    plot_running_in(profile, outdir / "running_in.png")
