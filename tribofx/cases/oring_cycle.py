"""The O-ring over a reciprocating stroke (``ehl-oring stroke=cycle``, issue 31).

The chapter (§8.1) solves the outstroke and the instroke as two steady states.
Here the rod runs U(t) = U cos(2πt/T) (T = ``period``): the cycle starts from
the steady outstroke at its peak speed (t = 0), reverses at T/4 (U = 0), runs
the instroke to T/2 … 3T/4 and the outstroke again.  The film is the seal's
transient JFO film (:mod:`tribofx.forms.squeeze`, ``scheme`` backward Euler or
BDF2) with the content's rate at the nodes (``lumped``,
:func:`tribofx.forms.jfo.jfo_on_surface`), stepped by :class:`tribofx.stepper.Stepper`
(Δt = T/``cycle_steps``, halved on Newton failure; a run that fails keeps and
writes its last converged step).

The ends of the film:

* the sealed end is flooded (p = p_s, λ = 0) in both strokes: an inlet in the
  outstroke, an outlet into the sealed fluid in the instroke;
* the air end is an open end (:meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.add_inflow`):
  a natural outlet in the outstroke; in the instroke an inlet supplied with the
  layer the rod carried out.  A rod point that passes the air end at time t in
  the instroke passed it at the mirror time 2t_r − t of the outstroke (t_r the
  reversal, the stroke being symmetric), carrying the content c = θh of the
  film there (the layer t = c/2 on the rod, brought back as c): the supply is
  the air end's content at the mirror time (the steady outstroke's before t = 0).

The Couette flux of the cavitated zone is integrated by the vertex rule in the
instroke (``vertex_couette`` ω = 1, :func:`reforming`): there the oil brought
back fills the film from the air end, and the Gauss-point product of θ and h
drains the node in front of the reforming film.  In the outstroke (ω = 0) the
film ruptures at the air-side outlet, where the vertex rule costs accuracy.
On the film arc refined once (``arc_refine=1``, 12.5 µm, the cycle's default:
:func:`tribofx.cases.film_setup.arc_halvings`) backward Euler and BDF2 run two
cycles, periodic from the second; at 25 µm the instroke's outlet constriction
is one node wide, h_min jumps from step to step and Newton may stall there.

A rough rod (``sigma`` > 0: Patir–Cheng flow factors and Greenwood–Tripp
asperities, :func:`tribofx.roughness.rough_pair`, boundary friction ``mu_b``)
carries the seal where the film collapses: at the reversal only the squeeze
holds a smooth film, and the starved instroke thins it further.

Records per step: ``time``, ``rod_speed``, ``h_min``, ``friction_force`` (the
film's axial force on the ring, pressure and shear, N on the whole circumference:
the steady strokes' ``friction_force_per_circumference`` × 2πr_rod), ``flux_air`` and
``flux_sealed`` (the volume fluxes out through the air end and in through the
sealed end, mm³/s, from the discrete rows:
:meth:`~tribofx.interfaces.reynolds_film.ReynoldsFilm.consistent_fluxes`),
``content`` (the oil in the film, mm³; its change over a step is the net flux
of the step, to the solver's tolerance); per completed cycle the net leakage
∫ flux_air dt (mm³, > 0 lost to the air side), the intake ∫ flux_sealed dt and
the change of the content.  The integrals Q are the scheme's own: the film's
difference of the content applied to Q, c₀(Q_{n+1} − Q_n) + c₁(Q_n − Q_{n−1}) =
Δt q(t_{n+1}) (backward Euler: Σ Δt_n q(t_{n+1})), with which intake − leakage
= change to the solver's tolerance for either scheme (a trapezoid would differ
by its error on the sealed end's flux, hundreds of mm³/s where the thick flank
breathes).
"""

import math

import numpy as np
from mpi4py import MPI

from ..forms.wear import bdf2_coefficients
from ..params import number_list
from ..roughness import rough_pair
from ..slow_run import SlowRun
from ..stepper import Stepper
from .oring_seal import build, solve_to

__all__ = ["AirLayer", "air_end", "cycle_stepper", "integral", "reforming", "rod_speed",
           "run_cycle", "transient_seal"]


def rod_speed(U, period):
    """Return t ↦ (0, U cos(2πt/T)) (mm/s), the rod's velocity in (r, z)."""
    return lambda t: np.array([0.0, U * math.cos(2 * math.pi * t / period)])


class AirLayer:
    """The layer the rod carries out at the air end and brings back (see the module docstring).

    ``history`` holds the outstroke's (t, c) at the air end, c = θh (mm); kept in
    the stepper's history, so a checkpoint carries it.
    """

    def __init__(self, history, period):
        self.h, self.period = history, float(period)
        self.h.setdefault("t", [])
        self.h.setdefault("c", [])

    def record(self, t, c, U):
        """Keep the content c (mm) at the air end at time t (s) while U > 0 (outstroke).

        A time not after the last one kept is skipped (a step cut and tried again
        records its start once).
        """
        if U > 0 and (not self.h["t"] or t > self.h["t"][-1]):
            self.h["t"].append(float(t))
            self.h["c"].append(float(c))

    def supply(self, t):
        """Content brought back at time t (mm): the air end's at the mirror time 2t_r − t."""
        if not self.h["t"]:
            return 0.0       # nothing carried out yet (the supply only acts in an instroke)
        T = self.period
        t_rev = (math.floor(t / T - 0.25) + 0.25) * T    # the last reversal out → in
        return float(np.interp(2 * t_rev - t, self.h["t"], self.h["c"]))


def reforming(U, T, t):
    """Return ω of the vertex-rule Couette flux at t: 1 in the instroke, 0 in the outstroke.

    In the instroke the starved film from the air end reforms in front of the
    contact; in the outstroke the film ruptures at the air-side outlet
    (:func:`tribofx.forms.jfo.jfo_on_surface`).
    """
    return 1.0 if rod_speed(U, T)(t)[1] < 0 else 0.0


def air_end(seal):
    """(θh, h, 2π r) at the air end of the film (the highest z of Γ_l), every rank."""
    prof = seal.film.profile(everywhere=True)
    k = int(np.argmax(prof["X"][:, 1]))
    return (1 - prof["lam"][k]) * prof["h"][k], prof["h"][k], 2 * math.pi * prof["x"][k, 0]


def transient_seal(v, U):
    """Build the seal of ``v`` at rod speed U (mm/s), its film transient (``scheme``), unsolved."""
    E_star = 3 * (v["mu1"] + v["mu2"]) / 0.75      # ν = 1/2, the rod rigid
    rough = rough_pair(v["sigma"], E_star, v["mu_b"]) if v["sigma"] > 0 else None
    return build(v, U, roughness=rough, transient=v["scheme"], name="ehl_oring_cycle")


def cycle_stepper(v, checkpoint=None, verbose=False, start=True, seal=None):
    """Build the seal of ``v`` at U, transient, solve its steady outstroke; return the Stepper.

    ``start``: mount and pressurise to the first p_s at U (False: a state to be
    restored from a checkpoint).  ``seal``: a seal of :func:`transient_seal` in
    the state to start from instead (nothing built or solved).  The schedule
    sets, at t_{n+1} of each step, the rod speed, the air end's supply
    (``stepper.layer``, an :class:`AirLayer`, which first records the air end's
    content of the state at t_n) and ω of :func:`reforming`; they are part of the
    state.  Returns the Stepper, with ``stepper.seal`` the
    :class:`~tribofx.cases.oring_seal.ORingSeal`.
    """
    U, T = v["U"], v["period"]
    if seal is None:
        seal = transient_seal(v, U)
        if start:
            solve_to(seal, v, U, number_list(v["p_s"], "p_s")[:1])
    film = seal.film
    layer = AirLayer({}, T)

    def supply(t):
        """Keep the layer of the state at t_n; return the supply brought back at t (s)."""
        layer.record(stepper.t, air_end(seal)[0], rod_speed(U, T)(stepper.t)[1])
        return layer.supply(t)

    stepper = Stepper(seal.components, film, parameters=[seal.p_s, seal.p_end],
                      checkpoint=checkpoint, name="ehl_oring_cycle", verbose=verbose,
                      problem_kw={"max_it": 40, "max_backtracks": 10,
                                  "line_search": "admissible", "stall_window": 10},
                      schedule=[(film.V_counter, rod_speed(U, T)),
                                (seal.supply, supply),
                                (film.vertex_couette, lambda t: reforming(U, T, t))])
    stepper.seal, stepper.layer = seal, layer
    return stepper


def run_cycle(case, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
    """Mount, pressurise to the first p_s at U, then step the cycles; returns the stepper."""
    T = v["period"]
    stepper = cycle_stepper(v, checkpoint, verbose, start=not resume)
    seal, film = stepper.seal, stepper.seal.film
    keys = ("time", "rod_speed", "h_min", "friction_force", "flux_air", "flux_sealed",
            "content", "supply")
    sr = SlowRun(stepper, v, record, keys, case.vtx_fields(seal), resume)
    stepper.layer.h = stepper.history.setdefault("air_layer", stepper.layer.h)  # on resume

    def log(st, its):
        u = float(film.V_counter.value[1])
        m = seal.measures()
        q_sealed, q_air = film.consistent_fluxes()
        sr.log(its, {"time": st.t, "rod_speed": u, "h_min": m["h_min"],
                     "friction_force": m["friction_force_per_circumference"] * 2 * math.pi
                     * seal.r_rod, "flux_air": q_air, "flux_sealed": q_sealed,
                     "content": film.content(), "supply": float(seal.supply.value)})

    if not resume:
        log(stepper, 0)
    sr.run(v["cycles"] * T, T / v["cycle_steps"], lambda st, rep: log(st, rep.iterations),
           progress, report=lambda: _report(sr.hist, record, T, seal, v["scheme"]))
    return stepper


def integral(t, q, scheme):
    """Q(t_n) = ∫₀^t_n q dt by the film's own scheme over the recorded steps ``t`` (s).

    c₀(Q_{n+1} − Q_n) + c₁(Q_n − Q_{n−1}) = Δt_{n+1} q(t_{n+1}), the weights of
    :meth:`~tribofx.interfaces.film_transient.TransientFilm.begin_step` (the first
    step, and every step of "euler", backward Euler).  A content whose rate is q
    changes by exactly Q.
    """
    Q, prev = np.zeros(len(t)), 0.0
    for n in range(len(t) - 1):
        dt = t[n + 1] - t[n]
        c0, c1 = (1.0, 0.0) if scheme == "euler" or prev <= 0 else bdf2_coefficients(dt / prev)
        dQ = Q[n] - Q[n - 1] if n > 0 else 0.0
        Q[n + 1] = Q[n] + (dt * q[n + 1] - c1 * dQ) / c0
        prev = dt
    return Q


def _report(hist, record, T, seal, scheme):
    """Per-step series, the leakage, intake and content change of each completed cycle, the film."""
    units = {"time": "s", "rod_speed": "mm/s", "h_min": "mm", "friction_force": "N",
             "flux_air": "mm^3/s", "flux_sealed": "mm^3/s", "content": "mm^3",
             "supply": "mm"}
    for key, vals in hist.items():
        record.result(key, vals, units[key])
    t = np.asarray(hist["time"])
    Q = {"leakage": integral(t, hist["flux_air"], scheme),
         "intake": integral(t, hist["flux_sealed"], scheme),
         "content_change": np.asarray(hist["content"])}
    per = {key: [] for key in Q}
    for k in range(int(t[-1] / T + 1e-9) if len(t) else 0):
        sel = np.flatnonzero((t >= k * T - 1e-12) & (t <= (k + 1) * T + 1e-12))
        for key, q in Q.items():
            per[key].append(float(q[sel[-1]] - q[sel[0]]))
    for key, vals in per.items():
        record.result(f"{key}_per_cycle", vals, "mm^3")
    if MPI.COMM_WORLD.rank == 0:
        record.profile = {"cycle": hist}
    record.result("time_reached", float(t[-1]) if len(t) else 0.0, "s")
    prof = seal.film.profile(everywhere=True)
    record.result("final_film", np.column_stack([prof["X"][:, 1], prof["h"], prof["p"],
                                                 prof["lam"]]).tolist(),
                  "mm (z), mm (h), MPa (p), - (λ) per node of the film at the last step")
