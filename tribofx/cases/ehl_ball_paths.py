"""Solution paths of the soft-EHL ball (chapter §8.3): position, load and speed control.

:class:`BallPaths` holds the continuation strategies of
:class:`tribofx.cases.ehl_ball.EHLBallCase` (its base class): the plane
position as the parameter of a secant on the load, the Hertz start of each
load, the thick-film path of large loads (displacement control at a higher
speed, then the speed marched down) and the speed marches; each strategy takes
the ``start`` position of a resumed sweep and reports its own position for the
checkpoint (:class:`tribofx.restart.SweepJournal`).  The case supplies
``hertz_contact``, ``scales``, ``set_scales`` and ``measures``.

* a(W) ≤ R/3 (W ≲ 12 N): each load starts from the Hertz state
  (:meth:`~tribofx.interfaces.Film.start_from_pressure`: the dry ball under the
  Hertz pressure, film of Hamrock–Dowson below the contact point) and the plane
  position is found by a secant on W (steps ≤ 0.1 δ_Hertz, films with min h ≤ 0
  rejected);
* larger loads (a → R/2, finite strain): at ``start_speed``·U (a film ≈ 9×
  thicker) from the Hertz state at min(W/steps, W/4), displacement control
  (:meth:`~tribofx.continuation.Continuation.advance`: the plane raised step by
  step, each step from the last converged state, step cutting), the load hit by
  the secant, then U continued down to U at fixed load (geometric march, the
  plane shifted by the Hamrock–Dowson film change); penalty, SUPG and tolerance
  scales follow load and speed.
"""

import numpy as np

from ..continuation import ConstantParameter, Continuation
from ..held_response import HeldResponse
from ..problem import NewtonDivergence

__all__ = ["Z", "BallPaths"]

Z = 2  # the plane's normal direction, index of its offset
#: largest speed ratio of one step of a speed march (a larger one starts the held-load
#: secant far from the new film: at 40 N the step 30U → U failed and was cut, 40 trials
#: each time; steps of ratio 2 converge in 2–3 position trials each)
MAX_SPEED_RATIO = 2.0


class BallPaths:
    """Continuation paths of the ball case (a base class of ``EHLBallCase``)."""

    @staticmethod
    def speed(run, on_set=None):
        """Entrainment speed U (mm/s) as a continuation parameter (the plane slides at 2U)."""
        return ConstantParameter(run[1].V_counter, 0, on_set=on_set, scale=2.0)

    @classmethod
    def hertz_start(cls, run, v, W, U):
        """Dry ball under the Hertz pressure at W, the plane at the film h_c(W, U) (all ranks)."""
        h = cls.hertz_contact(v, W)
        run[1].start_from_pressure(
            lambda x: h.pressure(np.hypot(x[0], x[1])),
            cls.scales(v, W, U)[2], np.zeros(3))

    @staticmethod
    def load(run):
        """Load W (N) carried by the film on the whole ball: twice the half model's F_z."""
        return 2.0 * float(run[1].force()[Z])

    @classmethod
    def position_control(cls, run, v, verbose=False, on_set=None, record=None):
        """Secant on the load W(z_p) in the plane position z_p (steps ≤ 0.1 δ_Hertz).

        A converged film with min h ≤ 0 or W ≤ 0 (an unphysical branch) is rejected.
        """
        film, problem = run[1], run[2]
        return Continuation(problem, ConstantParameter(film.counterpart.offset, Z, on_set),
                            response=lambda: cls.load(run), rtol=1e-4, max_trials=40,
                            verbose=verbose, max_step=0.1 * cls.hertz_contact(v).delta,
                            admissible=lambda: film.min_film() > 0 and cls.load(run) > 0,
                            record=record)

    @classmethod
    def hertz_slope(cls, v):
        """dW/dz_p = 1.5 W/δ(W) (N/mm) of a Hertz contact, as a function of W."""
        return lambda W: 1.5 * W / cls.hertz_contact(v, W).delta

    @classmethod
    def load_sweep(cls, run, v, on_step=None, verbose=False, start=None, on_accept=None):
        """Reach W/steps, …, W at the speed U; returns the position controller.

        ``on_step(W, iterations)`` after each load (the Newton trials of the
        load), then ``on_accept(position, carrier)``: the JSON ``position`` a
        resumed sweep starts from (``start=``, with the state of that load
        restored) and the arrays of the state the next load starts from (or None).
        """
        if cls.large_load(v):
            return cls.thick_film_sweep(run, v, on_step, verbose, start, on_accept)
        film, problem = run[1], run[2]
        W1 = v["W"] / v["steps"]
        inner = cls.position_control(run, v, verbose)
        offset = film.counterpart.offset.value
        # each trial sequence starts at the current position: the converged first
        # state, then the Hertz state predicted for each further load
        held = HeldResponse(inner, W1, slope=cls.hertz_slope(v), guess=lambda: float(offset[Z]))
        if start is None:
            cls.hertz_start(run, v, W1, v["U"])
            its0 = problem.solve_by_homotopy(verbose=verbose).iterations
            if not film.min_film() > 0:
                raise NewtonDivergence(
                    f"the first load W = {W1:g} N converged to a film with h <= 0 (contact "
                    "under-resolved by the mesh): raise mesh or use fewer load steps")
        else:
            inner.set_secant_state(start["inner"])
        for k in range(0 if start is None else start["k"], v["steps"]):
            if k > 0:
                held.predict = lambda W: cls.hertz_start(run, v, W, v["U"])
            held.target = v["W"] * (k + 1) / v["steps"]
            its = held.solve(verbose).iterations
            if on_step is not None:
                on_step(held.target, [its0, *its] if k == 0 else its)
            if on_accept is not None:
                on_accept({"k": k + 1, "inner": inner.secant_state()}, None)
        return inner

    @classmethod
    def thick_film_sweep(cls, run, v, on_step=None, verbose=False, start=None, on_accept=None):
        """Large loads: displacement control on a thick film at U_s, then continue down to U.

        (i) At U_s = ``start_speed``·U the Hertz state at W_0 = min(W/steps, W/4)
        is solved (if it fails: U_s ×0.3, ×3, ×0.1, ×10, never below U); (ii) the
        plane is raised by displacement control until the film carries the next
        load (:meth:`Continuation.advance`, scales following the load reached);
        (iii) from that state U is marched down to U at fixed load
        (:meth:`speed_march`) and the load recorded; (iv) the next load continues
        from the state at U_s (the ``carrier`` of ``on_accept``).  ``start``:
        as for :meth:`load_sweep`, with the carrier state restored.
        """
        film, problem = run[1], run[2]
        U, speed = v["U"], cls.speed(run)
        if start is None:
            its, k0 = [], 0
            W0 = min(v["W"] / v["steps"], 0.25 * v["W"])
            for f in (1.0, 0.3, 3.0, 0.1, 10.0):
                Us = max(U, f * v["start_speed"] * U)
                speed.set(Us)
                cls.set_scales(film, v, W0, Us)
                cls.hertz_start(run, v, W0, Us)
                try:
                    its = [problem.solve(verbose=verbose).iterations]
                except NewtonDivergence:
                    continue
                if film.min_film() > 0:
                    break
            else:
                raise NewtonDivergence(f"the start load W = {W0:g} N did not converge: change "
                                       "start_speed or mesh")
            W_start = cls.load(run)
        else:
            its, k0, Us, W_start = [], start["k"], start["Us"], start["W_start"]
            if k0 < v["steps"]:      # the next load starts from the thick-film state
                problem.restore(start["carrier"])
                speed.set(Us)
                cls.set_scales(film, v, W_start, Us)
            else:                    # all loads done: the last load's controller
                inner = cls.follow_control(run, v, W_start, W_start, verbose, its)
                inner.set_secant_state(start["inner"])
        for k in range(k0, v["steps"]):
            Wk = v["W"] * (k + 1) / v["steps"]
            inner = cls.follow_control(run, v, Wk, W_start, verbose, its)
            inner.advance(Wk, 0.05 * cls.hertz_contact(v).delta)
            cls.set_scales(film, v, Wk, Us)
            carrier = problem.state()
            if Us != U:  # (``inner`` records the Newton trials of each speed step)
                cls.speed_march(run, v, inner, Wk, U)
            if on_step is not None:
                on_step(Wk, its)
            if on_accept is not None:
                on_accept({"k": k + 1, "Us": Us, "W_start": Wk,
                           "inner": inner.secant_state()}, carrier)
            its, W_start = [], Wk
            if k + 1 < v["steps"] and Us != U:
                problem.restore(carrier)
                speed.set(Us)
                cls.set_scales(film, v, Wk, Us)
        return inner

    @classmethod
    def follow_control(cls, run, v, Wk, W_start, verbose=False, record=None):
        """Position control towards the load Wk whose scales follow the load reached.

        Every trial position sets the scales of the load reached last (≤ Wk;
        ``W_start`` before the first) at the current speed.
        """
        film, speed = run[1], cls.speed(run)

        def follow(z):
            W_ref = min(inner.history[-1][1], Wk) if inner.history else W_start
            cls.set_scales(film, v, W_ref, speed.get())

        inner = cls.position_control(run, v, verbose, on_set=follow, record=record)
        return inner

    @classmethod
    def speed_march(cls, run, v, inner, W, U, restart=False, record=None, on_speed=None,
                    increments=None):
        """Continue the converged state at load W in the entrainment speed to U (geometric).

        Each speed step re-finds the plane position for W (``inner``), starting
        from the Hertz state at the new speed (``restart``) or from the plane
        shifted by the Hamrock–Dowson change of the film, h_c((U_new/U_old)^0.64 − 1).
        A failed step is cut (six times at most).  ``on_speed(march)`` after every
        converged step; ``increments``: those of an interrupted march (resumed).
        """
        film = run[1]
        offset = film.counterpart.offset.value
        speed = cls.speed(run, on_set=lambda Uv: cls.set_scales(film, v, W, Uv))
        last = {"U": speed.get()}

        def shifted():
            h_c = cls.measures(run, v)["h_central"]
            return float(offset[Z]) - h_c * ((speed.get() / last["U"]) ** 0.64 - 1)

        def response():
            last["U"] = speed.get()
            return on_speed(march) if on_speed is not None else None

        held = HeldResponse(inner, W, slope=cls.hertz_slope(v),
                            guess=(lambda: float(offset[Z])) if restart else shifted,
                            predict=(lambda Wt: cls.hertz_start(run, v, Wt, speed.get()))
                            if restart else None)
        march = Continuation(held, speed, response=response, record=record)
        # speed ratios of at most MAX_SPEED_RATIO per step (a failed step is cut further)
        steps = max(1, int(np.ceil(abs(np.log(U / speed.get())) / np.log(MAX_SPEED_RATIO))))
        march.march(U, steps=steps, predictor=False, geometric=True, min_fraction=2.0**-6,
                    increments=increments)

    @classmethod
    def large_load(cls, v):
        """Return True when the Hertz radius a(W) exceeds R/3 (W > 11.9 N, default ball)."""
        return cls.hertz_contact(v).a > v["R"] / 3
