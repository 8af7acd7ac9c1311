"""Lifetimes of PETSc objects owned by problems: weak callbacks, collective destruction."""

from __future__ import annotations

import atexit
import weakref
from typing import TYPE_CHECKING, cast

from mpi4py import MPI

if TYPE_CHECKING:
    from collections.abc import Callable

    from dolfinx.fem.petsc import NonlinearProblem

    from .problem import Problem

__all__ = ["LIFETIMES", "weak_callback"]


def weak_callback[**P, R](method: Callable[P, R]) -> Callable[P, R]:
    """Wrap the bound ``method`` as a PETSc callback that does not keep its object alive.

    SNES keeps its callbacks in C, out of sight of Python's garbage collector: a
    bound method of the object that owns the SNES would make a cycle that is
    never collected, and every mesh, form and PETSc object of the problem —
    with the MPI communicators they duplicate — would leak (MPICH has 2048
    context ids per process, which a test-suite run without weak callbacks exhausts).
    """
    ref = weakref.WeakMethod(method)

    def call(*args: P.args, **kwargs: P.kwargs) -> R:
        return cast("Callable[P, R]", ref())(*args, **kwargs)  # called while its object lives

    return call


class _Lifetimes:
    """Collective destruction of the DOLFINx problems held by :class:`Problem` objects.

    ``dolfinx.fem.petsc.NonlinearProblem.__del__`` destroys its SNES and
    matrices at once, and destroying a parallel factorisation is collective.  A
    Problem caught in a reference cycle is freed by the cycle collector at a
    moment that differs from rank to rank, so that destruction would deadlock.
    On communicators of more than one rank the NonlinearProblem objects are
    therefore kept here (numbered in creation order, the same on every rank);
    a freed Problem only marks its number, and :meth:`release` — called by
    every rank at the same points (each Problem construction and solve, and at
    exit) — destroys those marked on all ranks, in creation order.  On one rank
    the object goes with its Problem.
    """

    live: dict[int, NonlinearProblem]
    dead: set[int]
    count: int

    def __init__(self) -> None:
        self.live, self.dead, self.count = {}, set(), 0

    def keep(self, problem: Problem, nlp: NonlinearProblem,
             comm: MPI.Comm) -> NonlinearProblem | None:
        """Hold ``nlp`` of ``problem`` until every rank has freed the problem."""
        if comm.size == 1:
            return nlp
        key = self.count
        self.count += 1
        self.live[key] = nlp
        weakref.finalize(problem, self.dead.add, key)
        return None

    def release(self, comm: MPI.Comm = MPI.COMM_WORLD, everything: bool = False) -> None:
        """Destroy, collectively, what every rank has freed (or ``everything``)."""
        if comm.size == 1 or not self.live:
            return
        if everything:
            keys = sorted(self.live)
        else:
            keys = sorted(set.intersection(*map(set, comm.allgather(sorted(self.dead)))))
        for k in keys:
            self.dead.discard(k)
            del self.live[k]


LIFETIMES = _Lifetimes()
atexit.register(lambda: LIFETIMES.release(everything=True))
