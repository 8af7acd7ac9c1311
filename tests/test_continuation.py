"""Continuation on a scalar toy problem whose solution is known in closed form.

The toy "problem" has one unknown x that its solve sets to g(d) = d³ + d for the
parameter d (no PDE, so the continuation logic alone is tested); a solve beyond
``d_fail`` diverges, and ``admissible`` can reject converged states.  The
response is x, so the parameter that reaches a target r solves d³ + d = r,
found independently here by ``numpy.roots``.
"""

import numpy as np
import pytest

from tribofx.continuation import Continuation
from tribofx.problem import NewtonDivergence


class Report:
    iterations = 1


class Toy:
    """x = d³ + d at the parameter d; solves beyond ``d_fail`` diverge."""

    def __init__(self, d_fail=np.inf):
        self.d, self.x, self.d_fail, self.solves = 0.0, 0.0, d_fail, 0

    # the parameter (ConstantParameter interface)
    def get(self):
        return self.d

    def set(self, value):
        self.d = float(value)

    # the problem interface
    def solve(self, verbose=False):
        self.solves += 1
        if self.d > self.d_fail:
            raise NewtonDivergence("toy diverged")
        self.x = self.d**3 + self.d
        return Report()

    def state(self):
        return self.x

    def restore(self, x):
        self.x = x

    def commit(self):
        pass


def root(r):
    """The real d with d³ + d = r (independent of the secant)."""
    z = np.roots([1.0, 0.0, 1.0, -r])
    return float(z[np.argmin(abs(z.imag))].real)


@pytest.mark.parametrize("max_step", [None, 0.2])
def test_reach_hits_the_target(max_step):
    toy = Toy()
    c = Continuation(toy, toy, response=lambda: toy.x, rtol=1e-10, max_step=max_step,
                     max_trials=60)
    d = c.reach(5.0, guess=0.5)
    # |x − 5| ≤ 5e-10 with dx/dd = 3d² + 1 ≥ 1 bounds the parameter error by 5e-10
    assert abs(d - root(5.0)) <= 5e-10
    assert c.history[-1][0] == d and abs(c.history[-1][1] - 5.0) <= 5e-10


def test_reach_gives_up_when_the_last_success_itself_fails():
    """Inadmissible beyond the last converged state: stop after the bound collapses.

    Every state with d > 0.5 is rejected, and the target (x = 5, d ≈ 1.52) lies
    beyond it.  The step-limited secant halves its bound from each failure; once
    it is below min_bound·max_step = 1e-4·0.2 the search must give up — after at
    most 1 + log2(0.2 / 2e-5) ≈ 15 failed trials past the last success, not
    ``max_trials`` — and restore the entry state and parameter.
    """
    toy = Toy()
    c = Continuation(toy, toy, response=lambda: toy.x, max_step=0.2, max_trials=200,
                     admissible=lambda: toy.d <= 0.5)
    with pytest.raises(NewtonDivergence, match="every trial within"):
        c.reach(5.0, guess=0.1)
    successes = int(np.ceil(0.5 / 0.2)) + 3   # steps of ≤ 0.2 (growing by 1.5) up to 0.5
    assert toy.solves <= successes + 15 + 1
    assert toy.d == 0.0 and toy.x == 0.0   # entry state and parameter restored


@pytest.mark.parametrize("offset", [0.0, 1e-14])
def test_reach_gives_up_when_the_converged_parameter_itself_fails(offset):
    """A solve that fails at the converged parameter (another parameter, e.g. a speed,
    has moved) is final: the plain secant halves its trial towards that parameter,
    so from a trial on it (or within round-off of it, ``offset`` relative, the
    first trial of a held response that barely moves) every retry is the same
    solve.  It gives up after that one trial, not after ``max_trials``, with the
    entry state and parameter restored."""
    toy = Toy()
    c = Continuation(toy, toy, response=lambda: toy.x, max_trials=30)
    c.reach(2.0, guess=0.9)
    d, x, solves = toy.d, toy.x, toy.solves
    toy.d_fail = -1.0                     # now every solve fails, at d as anywhere
    with pytest.raises(NewtonDivergence, match="fails at the converged parameter"):
        c.reach(2.0, guess=d * (1 + offset))
    assert toy.solves == solves + 1
    assert (toy.d, toy.x) == (d, x)


def test_march_cuts_failed_steps_and_reaches_the_target():
    """Natural-parameter march to d = 1 in one step with solves failing beyond d = 0.3.

    The failure threshold moves up after each converged step (a path that only
    small steps can follow): the march must cut, converge and end exactly at 1.
    """
    toy = Toy(d_fail=0.3)
    commit = toy.commit
    toy.commit = lambda: (commit(), setattr(toy, "d_fail", toy.d + 0.3))
    c = Continuation(toy, toy, response=lambda: toy.x)
    c.march(1.0, steps=1, predictor=False)
    assert toy.d == 1.0 and abs(toy.x - 2.0) <= 1e-15
    assert all(b - a <= 0.3 + 1e-15 for a, b in zip([0.0] + [h[0] for h in c.history],
                                                     [h[0] for h in c.history]))


@pytest.mark.parametrize("regrow, failures", [(1, 9), (3, 5)])
def test_march_regrows_a_cut_increment_after_regrow_steps(regrow, failures):
    """A march to d = 2 in one increment where every increment above 0.3 fails.

    The increment is cut 2 → 1 → 0.5 → 0.25 (3 failures); it then doubles back
    to 0.5 (which fails) after ``regrow`` steps converged at 0.25.  Counted by
    hand: with 1, each 0.25 step from 0.25 to 1.5 is followed by a failed 0.5
    (3 + 6 failures; from 1.75 the last increment is 0.25); with 3, the 0.5 is
    retried from 0.75 and from 1.5 only (3 + 2 failures).  The accepted path is the same: steps of
    0.25 ending exactly at 2."""
    toy = Toy(d_fail=0.3)
    commit = toy.commit
    toy.commit = lambda: (commit(), setattr(toy, "d_fail", toy.d + 0.3))
    c = Continuation(toy, toy, response=lambda: toy.x)
    c.regrow = regrow
    c.march(2.0, steps=1, predictor=False)
    assert [h[0] for h in c.history] == [0.25 * k for k in range(1, 9)]
    assert toy.solves - len(c.history) == failures
