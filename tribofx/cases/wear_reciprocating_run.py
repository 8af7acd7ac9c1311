"""The slow time of the reciprocating pin on a block: load-up, cycles, snapshots, report.

:class:`ReciprocatingRun` is a base class of
:class:`tribofx.cases.wear_reciprocating.WearReciprocatingCase`: the load-up, the
run over ``cycles`` through :class:`tribofx.slow_run.SlowRun` (energy balance of
the drive per cycle), the worn shapes of both bodies before and after, the plots.

Results per slow step: ``time``, ``cycles_done``, ``worn_area_pin`` and
``worn_area_block`` (∫ (1 − det G) dV̂, mm² per mm), ``dissipated_energy`` (the
frictional dissipation of the cycles so far, N·mm per mm), ``drive_work`` and
``drive_work_bound`` (the work of the block's drive over the last cycle, ∮ F_x dx
by the trapezoidal rule, and the bound ½ Σ |ΔF_x||Δx| of that rule),
``rate_integral_pin``/``_block`` (∫ W̄̇ dŜ of the step's averaged rate, mm²/(mm·s)),
``normal_force`` (the contact force on the pin along y at the solved state of
the step: F, by the pin's vertical equilibrium, to ``normal_force_bound`` = n_u ·
atol_u of the pin's momentum rows), and the final worn profiles of both bodies;
``pin_series.bp`` and ``block_series.bp`` (VTX time series of u and w at every
slow step: warp by w for the worn shape, by u for the deformed one); ``fig5.png``
(initial and worn, undeformed and deformed, both bodies, at −A, at the centre
and at +A) and ``wear.png``.
"""

import math

import numpy as np
import ufl
from mpi4py import MPI

from ..continuation import ConstantParameter, Continuation
from ..references import hertz
from ..slow_run import SlowRun
from ..stepper import nominal_steps
from . import slow_time
from .wear import WearPinCase

__all__ = ["ReciprocatingRun", "cell_coordinates"]


def cell_coordinates(body):
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
    w = body.w.x.array.reshape(-1, 2)[dofs]
    parts = msh.comm.gather((X, w, u), root=0)
    if msh.comm.rank != 0:
        return None
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(3))


def _jsonable(shot):
    """Return a :meth:`WearReciprocatingCase.snapshot` as nested lists (None off rank 0)."""
    if shot is None or any(body is None for part in shot for body in part):
        return None
    return [[[np.asarray(a).tolist() for a in body] for body in part] for part in shot]


def _arrays(shot):
    """Return the arrays of a :func:`_jsonable` snapshot."""
    if shot is None:
        return None
    return [[tuple(np.asarray(a) for a in body) for body in part] for part in shot]


class ReciprocatingRun:
    """The slow time of the reciprocating pin on a block: load-up, cycles, snapshots, report."""

    @classmethod
    def progress_total(cls, v):
        """Return the slow steps the progress bar counts: nominal steps to T = cycles·Δτ."""
        return nominal_steps(v["cycles"] * cls.period(v), v["dt"])

    @staticmethod
    def load_up(run, v, verbose=False):
        """Press the pin onto the block under F (load factor 0 → 1); Newton iterations.

        Newton starts from the pin translated down by the Hertz approach a²/(2R)
        of the tip (2D Hertz, both moduli) plus its compression F H/(W E_pin); a
        user's pin (``mesh_file``) by its tip height at |x| = W/4 plus F H/(ℓ E_pin)
        (:meth:`tribofx.cases.wear.WearPinCase._user_approach` with the pin's
        traction q = F/ℓ and modulus).
        """
        if v["mesh_file"]:
            delta0 = WearPinCase._user_approach(
                run["wear_pin"].contact, {"q": v["F"] / run["top_length"], "E": v["E_pin"]})
        else:
            a = min(hertz(v["F"], v["R_tip"], v["E_pin"], v["nu"], math.inf, v["E_block"],
                          v["nu"], line=True).a, v["W"] / 2)
            delta0 = a * a / (2 * v["R_tip"]) + v["F"] * v["H"] / (v["W"] * v["E_pin"])
        run["pin"].u.x.array.reshape(-1, 2)[:, 1] = -delta0
        run["load"].value = 0.0
        control = Continuation(run["stepper"].problem, ConstantParameter(run["load"]),
                               verbose=verbose)
        control.march(1.0, steps=2, predictor=False)
        return int(sum(control.record))

    @staticmethod
    def snapshot(run):
        """Cells of both bodies (X̂, w, u) at −A, at the centre and at +A of a cycle (rank 0).

        Runs the start of a cycle at the current shapes: memory erased, the
        block at −A (a), the run-in to the centre (b), the first quarter to +A
        (c); then restarts, so the state is that of a cycle start again.
        """
        st, cyc = run["stepper"], run["cycle"]
        P = st.problem
        shots = []
        cyc.start()
        P.commit()
        P.solve_by_homotopy()
        P.commit()
        shots.append([cell_coordinates(run["pin"]), cell_coordinates(run["block"])])
        for pos in cyc.run_in:
            cyc.move(pos)
            P.solve_by_homotopy()
            P.commit()
        shots.append([cell_coordinates(run["pin"]), cell_coordinates(run["block"])])
        for pos in cyc.positions[:cyc.fast_steps // 4]:
            cyc.move(pos)
            P.solve_by_homotopy()
            P.commit()
        shots.append([cell_coordinates(run["pin"]), cell_coordinates(run["block"])])
        st.restart()
        return shots

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
        """Load, then integrate the wear of both bodies over ``cycles``; per-step histories.

        ``checkpoint``: directory of the per-step checkpoint (state and histories);
        ``resume``: continue from it (:mod:`tribofx.restart`).
        """
        run = cls.build(v, checkpoint=checkpoint)
        st, contact, cycle = run["stepper"], run["contact"], run["cycle"]
        wp, wb = run["wear_pin"], run["wear_block"]
        st.verbose = verbose
        for key, val, unit in (("pin_width", run["W"], "mm"), ("pin_height", run["H"], "mm"),
                               ("pin_top_length", run["top_length"], "mm"),
                               ("contact_element_size", run["h"], "mm")):
            record.result(key, val, unit)
        pin = run["pin"]
        # the pin's vertical equilibrium: Σ of its momentum rows along y (each below
        # atol_u at a solved state) is F − (contact force along y)
        record.result("normal_force_bound", pin.V.dofmap.index_map.size_global * 2
                      * pin.tolerances()[pin.u].atol, "N/mm")
        tau = cls.period(v)
        # the worn shapes and the deformation at every slow step (ParaView time series)
        sr = SlowRun(st, v, record, (
            "time", "cycles_done", "worn_area_pin", "worn_area_block", "dissipated_energy",
            "cycle_dissipation", "drive_work", "drive_work_bound", "friction_force_ratio",
            "rate_integral_pin", "rate_integral_block", "normal_force", "newton_iterations",
            "picard_iterations", "dt", "error_estimate", "rejected"), cls.vtx_fields(run),
            resume)
        h, hist = sr.history, sr.hist
        energy = [hist["dissipated_energy"][-1] if resume else 0.0]
        w_ref = contact.surface.nodal(ufl.TestFunction(contact.Q) * contact.dsc)

        def log(t, dt, its, picard=0, error=None, rejected=0):
            comm = contact.slave.mesh.comm
            if st.last_increments is not None:   # dissipation of the step's (last) cycle
                d_pin = st.last_increments[0]
                n = contact.Q.dofmap.index_map.size_local
                cyc_d = comm.allreduce(float(d_pin[:n] @ w_ref[:n]), op=MPI.SUM) / v["K_pin"]
                energy[0] += cyc_d * dt / tau
            else:
                cyc_d = None
            sr.log(its, (("time", t), ("cycles_done", t / tau),
                         ("worn_area_pin", wp.worn_volume()),
                         ("worn_area_block", wb.worn_volume()),
                         ("dissipated_energy", energy[0]), ("cycle_dissipation", cyc_d),
                         ("drive_work", cycle.work), ("drive_work_bound", cycle.work_bound),
                         ("friction_force_ratio", cycle.sliding_force_ratio(v["F"])),
                         ("rate_integral_pin", wp.wear_rate_integral()),
                         ("rate_integral_block", wb.wear_rate_integral()),
                         ("normal_force", float(contact.forces()[0][1])),
                         ("newton_iterations", its), ("picard_iterations", picard),
                         ("dt", dt), ("error_estimate", error), ("rejected", rejected)))

        if not resume:
            log(0.0, 0.0, cls.load_up(run, v, verbose))
            h["initial_shot"] = _jsonable(cls.snapshot(run))
        shots = {"initial": _arrays(h["initial_shot"])}

        def report():
            cls._report(run, record, hist, shots)
            if record.profile is not None:
                half = 0.5 * v["L"] + v["A"] + 0.1
                record.profile["view"] = ((-half, half), (-v["D"] - 0.1, 0.6 * run["H"]))

        sr.run(v["cycles"] * tau, v["dt"],
               lambda s, rep: log(s.t, rep.dt, rep.iterations, rep.picard, rep.error,
                                  rep.rejected), progress,
               report=report, problem=run, **slow_time.control(v),
               after=lambda: shots.__setitem__("worn", cls.snapshot(run)))
        return run

    @staticmethod
    def _report(run, record, hist, shots):
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
        prof = {}
        for key in ("wear_pin", "wear_block"):
            d = run[key].gather_shape()
            if d is not None:
                prof[key] = {"X_hat": d["X_hat"], "X_worn": d["X_worn"], "x": d["x"],
                             "depth": d["depth"]}
                record.result(f"final_profile_{key[5:]}", d["X_worn"].tolist(),
                              "mm (worn configuration)")
                record.result(f"final_depth_{key[5:]}", d["depth"].tolist(), "mm")
        if MPI.COMM_WORLD.rank == 0:
            record.profile = {**hist, **prof, "shots": shots}

    @staticmethod
    def vtx_fields(run):
        """Displacement and shape change of both bodies (one file per mesh)."""
        return {"pin": [run["pin"].u, run["pin"].w], "block": [run["block"].u, run["block"].w]}

    @staticmethod
    def plot(profile, outdir):
        """``fig5.png`` (configurations, both bodies) and ``wear.png`` (histories, profiles)."""
        from ..plots.two_body import plot_reciprocating

        plot_reciprocating(profile, outdir)
