"""A slow-time run of a :class:`tribofx.stepper.Stepper`: its records, series and failure.

Every wear case integrates its stepper from t = 0 (or a checkpoint) to T; what
it needs besides its physics is the same and lives here:

* the per-step records (``hist``: lists keyed by measure; ``newton_iterations``)
  kept in the stepper's ``history``, so the checkpoint written after every step
  carries them and ``--resume`` continues them (:func:`tribofx.restart.open_history`
  checks the checkpoint's parameters);
* a ParaView time series of the case's fields at every accepted step (a resumed
  run writes its steps into series of their own, :func:`tribofx.restart.series_stem`);
* the run itself: :meth:`SlowRun.run` calls ``Stepper.run`` (step cutting,
  checkpoint, interruption), writes the series after the case's ``on_step``,
  and whatever happens closes the series and writes the case's report; a failed
  or interrupted run carries ``problem`` = the stepper (or the case's run) at its
  last accepted step.

The case keeps its measures (what one step logs) and its report.
"""

from . import interrupt
from .output import VTXSeries
from .problem import NewtonDivergence
from .restart import open_history, series_stem

__all__ = ["SlowRun", "wear_fields"]


def wear_fields(wear):
    """VTX fields of a worn body: displacement and shape change (bulk), contact multiplier."""
    return {"displacement": [wear.body.u, wear.body.w], "contact": [wear.contact.lam_n]}


class SlowRun:
    """Records, series and failure handling of one slow-time run of ``stepper``.

    Args:
        stepper: the :class:`tribofx.stepper.Stepper`.
        v: the run's parameter values (checked against a checkpoint on resume).
        record: the run record (``data``, ``result``, ``outdir``).
        keys: the names of the per-step measures (``hist[key]`` lists).
        fields: ``{name: [Function, ...]}`` written as ``<name>_series.bp``.
        resume: continue from the stepper's checkpoint.
    """

    def __init__(self, stepper, v, record, keys, fields, resume=False):
        self.stepper, self.record = stepper, record
        record.data["num_dofs"] = stepper.problem.num_dofs
        if stepper.shape is not None:
            record.data["num_dofs_shape"] = stepper.shape.num_dofs
        self.history = open_history(stepper, v, resume)
        self.hist = self.history.setdefault("hist", {k: [] for k in keys})
        record.data["newton_iterations"] = self.history.setdefault("newton_iterations", [])
        self.series = VTXSeries(stepper.comm, getattr(record, "outdir", None),
                                {series_stem(f"{k}_series", stepper, resume): f
                                 for k, f in fields.items()})

    def log(self, iterations, values):
        """Append the step's measures ``values`` (pairs or a dict) and its Newton iterations."""
        for key, val in (values.items() if isinstance(values, dict) else values):
            self.hist[key].append(val)
        self.record.data["newton_iterations"].append(iterations)

    def run(self, T, controller, on_step=None, progress=None, report=None, problem=None,
            after=None):
        """Integrate to ``T`` (s), the steps by ``controller``; the series at every step.

        ``controller``: a step (s) or a :class:`tribofx.step_control.StepController`
        (:meth:`tribofx.stepper.Stepper.run`).  ``on_step(stepper, report)``
        after every accepted step (before its series entry); ``report()`` at
        the end whatever happens; ``problem``: what a failure carries (default
        the stepper); ``after()`` once the run has reached T, before the report
        (a failure there carries ``problem`` too).
        """
        st = self.stepper
        self.series.write(st.t)

        def step(s, rep):
            if on_step is not None:
                on_step(s, rep)
            self.series.write(s.t)

        try:
            st.run(T, controller, on_step=step, progress=progress)
            if after is not None:
                after()
        except (NewtonDivergence, interrupt.Interrupted) as err:
            err.model = st if problem is None else problem
            raise
        finally:
            self.series.close()
            if report is not None:
                report()
