"""Stop a long run between steps on SIGINT/SIGTERM, with its last converged state kept.

:func:`watch` installs handlers that only set a flag (a signal never interrupts
a Newton solve or a checkpoint write); :func:`check`, called by the slow-time
loop after each accepted step and its checkpoint, raises :class:`Interrupted`
on every rank when any rank got a signal (one MPI reduction per step).  The
runner then writes the summary and the VTX output of that state; the CLI exits
with status 130, and ``tribofx run ... --resume`` continues from the checkpoint.
A second signal stops the process at once (default action).
"""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

from mpi4py import MPI

from .reports import RunStop

__all__ = ["Interrupted", "arm", "check", "watch"]

_flag = {"signal": 0, "active": False}
_SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(RunStop):
    """A run stopped by SIGINT/SIGTERM after an accepted (checkpointed) step."""


def _handler(signum: int, frame: FrameType | None) -> None:
    if _flag["signal"]:          # a second signal: stop now, the default way
        signal.signal(signum, signal.SIG_DFL)
        os.kill(os.getpid(), signum)
        return
    _flag["signal"] = signum


def arm() -> None:
    """(Re-)install the handlers inside :func:`watch`.

    Libraries initialised after :func:`watch` replace them (gmsh resets SIGTERM
    to its default, PETSc installs its own abort handler), so the slow-time loop
    arms them again before its first step and after every check.
    """
    if _flag["active"]:
        for s in _SIGNALS:
            signal.signal(s, _handler)


@contextmanager
def watch() -> Iterator[None]:
    """Within the block, SIGINT and SIGTERM set a flag for :func:`check`."""
    old = {s: signal.getsignal(s) for s in _SIGNALS}
    _flag.update(signal=0, active=True)
    arm()
    try:
        yield
    finally:
        _flag["active"] = False
        for s, h in old.items():
            signal.signal(s, h if h is not None else signal.SIG_DFL)


def check(comm: MPI.Comm, t: float | None = None) -> None:
    """Raise :class:`Interrupted` on all ranks of ``comm`` if any rank got a signal."""
    got = comm.allreduce(_flag["signal"], op=MPI.MAX)
    arm()
    if got:
        name = signal.Signals(got).name
        raise Interrupted(f"{name} received; stopped after the step to t = {t:g} s"
                          if t is not None else f"{name} received")
