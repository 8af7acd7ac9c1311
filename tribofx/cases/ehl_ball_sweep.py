"""The load and speed sweeps of the soft-EHL ball (chapter §8.3), journalled per variant.

:class:`BallSweep` is a base class of :class:`tribofx.cases.ehl_ball.EHLBallCase`:
the variants of ``compare``, each a :class:`tribofx.sweep.SweepVariant` running the
loads and then the speeds of ``speeds`` along the paths of
:class:`tribofx.cases.ehl_ball_paths.BallPaths`.
"""

import numpy as np
from mpi4py import MPI

from ..problem import options_name
from ..references import hamrock_dowson
from ..restart import SweepJournal
from ..sweep import SweepVariant
from .ehl_ball_mesh import MAX_EDGE_RATIO, edge_size, mesh_levels, outlet_width

__all__ = ["BallSweep"]


class BallSweep:
    """The load and speed sweeps of the soft-EHL ball (chapter §8.3), journalled per variant."""

    @classmethod
    def progress_total(cls, v):
        """Points the progress bar counts: the loads of every variant."""
        return v["steps"] * (len(cls.VARIANTS) if v["compare"] == "all" else 1)

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
        """Load sweep (and speed sweep) of each variant; results prefixed by the variant.

        ``checkpoint``: directory of the sweep's checkpoint, written after every
        converged load and speed step (:class:`tribofx.restart.SweepJournal`);
        ``resume``: continue from it.
        """
        variants = cls.VARIANTS if v["compare"] == "all" else (("", v["model"], {}),)
        journal = SweepJournal(checkpoint, MPI.COMM_WORLD, v, resume)
        record.result("mu_U", v["mu"] * v["U"], "N/mm")
        a, p0, _, _ = cls.scales(v)
        hc, hm = hamrock_dowson(v["W"], v["mu"], v["U"], v["R"], cls.e_star(v))
        for key, value in (("hertz_a", a), ("hertz_p0", p0), ("hamrock_dowson_h_c", hc),
                           ("hamrock_dowson_h_min", hm)):
            record.result(key, value, "MPa" if key == "hertz_p0" else "mm")
        if not v["mesh_file"]:
            level, refine, resolved = mesh_levels(v)
            record.data["mesh_levels"] = {"mesh": level, "edge_refine": refine}
            if not resolved:
                record.warn(f"mesh={level} edge_refine={refine}: elements of "
                            f"{edge_size(v, level, refine):.3g} mm along the contact edge "
                            f"> {MAX_EDGE_RATIO:g} × the outlet width {outlet_width(v):.3g} mm "
                            "at this W and U: expect a zig-zag or a spurious dip of the film")
        record.data["variant_newton_iterations"] = {}
        record.profile = {"variants": {}, "W": v["W"]}
        first = None
        for name, label, over in variants:
            run = cls.sweep(dict(v, **over), name, label, record, journal, progress, verbose)
            first = first or run
        return first

    @classmethod
    def sweep(cls, vv, name, label, record, journal, progress=None, verbose=False):
        """Run the loads, then the speeds of ``speeds``, of one variant; returns its run.

        After every converged load and speed step the variant's state, records
        and position are written to ``journal`` (position: ``leg`` 0 the loads,
        1 + j the march to the j-th speed; the secant state of the position
        search; the march increments; the film scales); a resumed variant
        restores them and continues on the same sequence of steps.
        """
        key = name or vv["model"]
        run = cls.build(vv, name=options_name("ehl_ball", name))
        film, problem = run[1], run[2]
        record.data["num_dofs"] = problem.num_dofs
        # (the plane's offset is state); the series' "time" is the point's index, its
        # (W, U) in series_points
        sv = SweepVariant(journal, key, run, problem.state_fields() + [film.V_counter],
                          record, cls.vtx_fields(run), f"{name}_" if name else "",
                          ("steps", "speed"), run[0].mesh.comm, progress)
        steps, speed, its_all = sv["steps"], sv["speed"], sv["its"]
        pos = sv.position
        record.data["variant_newton_iterations"][key] = its_all
        var = {"label": label, "shear": vv["shear"]}
        record.profile["variants"][key] = var
        at = {"leg": 0 if pos is None else pos["leg"]}

        def write():
            sv.write([cls.load(run), cls.speed(run).get()])

        def save(position, arrays=None):
            sv.save(dict(position, leg=at["leg"], scales=film.scale_values()),
                    arrays=[] if arrays is None else arrays)

        def on_step(W, its):
            its_all.append([i for t in its for i in (t if isinstance(t, list) else [t])])
            if steps:   # the film map is kept for the last load only (checkpoint size)
                steps[-1].pop("profile", None)
            steps.append(cls.measures(run, vv))
            write()
            if progress is not None:
                progress.update(1)

        def on_speed(march=None):
            m = cls.measures(run, vv)
            m.pop("profile")
            speed.append(dict(m, U=cls.speed(run).get()))
            write()
            if march is not None:
                save({"increments": march.increments, "inner": inner.secant_state()})

        start = None
        if pos is not None:
            carrier = sv.resume()
            film.set_scales(**pos["scales"])
            problem.refresh()
            start = dict(pos, carrier=carrier)
        with sv:
            try:
                if at["leg"] == 0:
                    inner = cls.load_sweep(run, vv, on_step, verbose, start, on_accept=save)
                    if cls.speed_list(vv):
                        on_speed()
                elif cls.large_load(vv):
                    inner = cls.follow_control(run, vv, vv["W"], vv["W"], verbose)
                    inner.set_secant_state(pos["inner"])
                else:
                    inner = cls.position_control(run, vv, verbose)
                    inner.set_secant_state(pos["inner"])
                for j, U in enumerate(cls.speed_list(vv)):
                    if j + 1 < at["leg"]:
                        continue
                    increments = pos["increments"] if j + 1 == at["leg"] else None
                    at["leg"] = j + 1
                    cls.speed_march(run, vv, inner, vv["W"], U,
                                    restart=not cls.large_load(vv), record=its_all,
                                    on_speed=on_speed, increments=increments)
            finally:
                if steps:
                    var.update({k: np.asarray(x) for k, x in steps[-1]["profile"].items()})
                cls._report(steps, speed, vv, record, f"{name}_" if name else "")
                var["speed"] = {k: [m[k] for m in speed] for k in (
                    "mu_U", "friction_coefficient", "couette_friction_coefficient",
                    "plane_friction_coefficient")}
        return run
