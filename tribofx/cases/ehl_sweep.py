"""The load sweep (and speed continuation) of the coated layer (chapter §8.2), per variant.

:class:`CylinderSweep` is a base class of
:class:`tribofx.cases.ehl.EHLCylinderLayerCase`: the variants of ``compare``, each a
journalled :class:`tribofx.sweep.SweepVariant` along the paths of
:class:`tribofx.cases.ehl_paths.CylinderPaths`.
"""

from mpi4py import MPI

from ..problem import options_name
from ..restart import SweepJournal
from ..sweep import SweepVariant

__all__ = ["CylinderSweep"]


class CylinderSweep:
    """The load sweep (and speed continuation) of the coated layer (chapter §8.2), per variant."""

    @classmethod
    def sweep(cls, v, record, progress=None, verbose=False, prefix="", journal=None):
        """Load sweep (and speed continuation) of one variant; results prefixed ``prefix``.

        ``journal``: a :class:`tribofx.restart.SweepJournal`; the state, the
        records and the position (leg 0: the loads, leg 1 + j: the march to the
        j-th speed; its increments; the inner position search) are written after
        every converged load and speed (:class:`tribofx.sweep.SweepVariant`), and a
        resumed variant continues there.
        """
        name = prefix[:-1] or v["model"]
        run = cls.build(v, name=options_name("ehl_cylinder", prefix[:-1]))
        layer, film, problem = run
        journal = journal or SweepJournal(None, layer.mesh.comm, v)
        record.data["num_dofs"] = problem.num_dofs
        var = SweepVariant(journal, name, run, problem.state_fields() + [layer.velocity],
                           record, cls.vtx_fields(run), prefix, ("steps", "speed", "profiles"),
                           layer.mesh.comm, progress)
        steps, speed, profiles, its = (var[k] for k in ("steps", "speed", "profiles", "its"))
        pos = var.position

        def write(m):
            var.write([m["W"], float(layer.velocity.value[0])])

        def save(leg, march):
            var.save({"leg": leg, "increments": march.increments,
                      "W": loads.done if leg == 0 else v["W"], "inner": inner.secant_state(),
                      "scales": film.scale_values()})

        def on_step():
            m = cls.measures(run, v)
            profiles.append(dict(m.pop("profile"), W=m["W"]))
            steps.append(m)
            write(m)
            if progress is not None:
                progress.update(1)

        def on_speed():
            m = cls.measures(run, v)
            m.pop("profile")
            m["U"] = float(layer.velocity.value[0])
            speed.append(m)
            write(m)

        if prefix:
            record.data.setdefault("variant_newton_iterations", {})[name] = its
        loads, inner = cls.load_control(run, v, on_step, verbose, its,
                                         on_accept=lambda: save(0, loads))
        leg = 0 if pos is None else pos["leg"]
        if pos is not None:
            var.resume()
            film.set_scales(**pos["scales"])
            problem.refresh()
            loads.resume_from(pos["W"])
            inner.set_secant_state(pos["inner"])
        increments = None if pos is None else pos["increments"]
        with var:
            try:
                if leg == 0:
                    loads.march(v["W"], v["steps"], predictor=False, increments=increments)
                    increments = None
                if cls.speed_list(v):
                    if leg == 0:
                        speed.append(dict(steps[-1], U=v["U"]))
                    cls.speed_sweep(run, v, inner, v["W"], cls.speed_list(v), on_speed, its,
                                    start=max(leg - 1, 0), increments=increments,
                                    on_accept=lambda j, march: save(1 + j, march))
            finally:
                cls._report(steps, speed, profiles, v, record, prefix)
        return run

    @classmethod
    def run(cls, v, record, progress=None, verbose=False, checkpoint=None, resume=False):
        """Load sweep W/steps … W (per variant of ``compare``); records the film measures.

        ``checkpoint``: directory of the sweep's checkpoint (written after every
        converged load and speed); ``resume``: continue from it.
        """
        journal = SweepJournal(checkpoint, MPI.COMM_WORLD, v, resume)
        record.result("mu_U", v["mu"] * v["U"], "N/mm")
        if v["compare"] == "none":
            return cls.sweep(v, record, progress, verbose, journal=journal)
        record.result("variants", [name for name, _, _ in cls.COMPARE[v["compare"]]])
        first = None
        for name, label, over in cls.COMPARE[v["compare"]]:
            run = cls.sweep(dict(v, **over), record, progress, verbose, prefix=f"{name}_",
                            journal=journal)
            first = first or run
            if MPI.COMM_WORLD.rank == 0:
                record.profile["variants"][name]["label"] = label
                record.profile["compare"] = v["compare"]
        return first
