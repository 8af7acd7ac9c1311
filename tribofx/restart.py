"""Resuming a slow-time run from its checkpoint (``tribofx run ... --resume``).

A resumable case's ``run(v, record, ..., checkpoint, resume)`` builds its
:class:`tribofx.stepper.Stepper` with ``checkpoint=DIR`` (the state is written
after every accepted step, with :attr:`Stepper.history`, the case's records
so far) and calls :func:`open_history` before its first step:

* a fresh run: the history starts empty, with the physical parameters in it;
* ``resume=True``: the stepper's state and history are read back, and the
  parameters of the checkpoint must be the run's (the solver strategy may
  differ: it does not change the answer beyond the solver tolerance).

The case keeps every record it reports in the returned dict (JSON types
only), so a resumed run reports the whole time series.  A resumed run writes
its VTX series into files of their own (:func:`series_stem`), beside the
series of the interrupted run.
"""

import json

from .params import InputError

__all__ = ["open_history", "series_stem"]

#: parameters that select how the problem is solved, not which problem
SOLVER_PARAMETERS = ("solver",)


def open_history(stepper, v, resume):
    """Read back the checkpoint when resuming; return ``stepper.history``.

    ``v``: the run's parameter values.  Raises :class:`InputError` (one line)
    for an incomplete checkpoint, one written on another number of ranks, or
    with other physical parameters.
    """
    params = {k: x for k, x in v.items() if k not in SOLVER_PARAMETERS}
    if resume:
        try:
            stepper.load_checkpoint()
        except (ValueError, OSError, KeyError) as err:
            raise InputError(f"cannot resume: {err}") from None
        saved = stepper.history.get("parameters")
        now = json.loads(json.dumps(params))     # as the checkpoint holds them
        if saved is not None and saved != now:
            diff = sorted(k for k in set(saved) | set(now) if saved.get(k) != now.get(k))
            raise InputError(f"--resume with other parameters than the checkpoint's "
                             f"({', '.join(diff)})")
    stepper.history.setdefault("parameters", params)
    return stepper.history


def series_stem(stem, stepper, resume):
    """File stem of a VTX series: a resumed run's series starts at its restart time."""
    return stem + (f"_from_t{stepper.t:g}" if resume else "")
