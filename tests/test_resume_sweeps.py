"""A continuation sweep stopped by a signal between points and resumed: the uninterrupted result.

The EHL cases march loads, then speeds or sealed pressures, per variant of the
model or stroke; after every recorded point they write the state, the records
and the position in the sweep (leg, march increments, the inner secant's
history, the film scales, and for the ball at large loads the thick-film state
the next load starts from: :class:`tribofx.restart.SweepJournal`) into
``--out/checkpoint``.  Reference: the same run without interruption.

Tolerance: the restored state is the checkpoint's arrays exactly and the
resumed sweep takes the same parameter values with the same first trials, so
the runs can differ only through round-off of the linear solves after the
restart (a fresh MUMPS factorisation), amplified at most to the stopping
tolerances of what follows: the position secants stop at a relative 1e-6 of W
(cylinder layer) and 1e-4 (ball), Newton far below.  We assert 1e-6 relative
(1e-4 for the ball) of each quantity's largest magnitude; in practice the runs
agree to the last digit and the Newton iteration counts are equal, which is
asserted too.
"""

import json
import re
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from test_resume import ENV, _cli, stop_then_resume

from tribofx.output import bp4_steps

# case: (arguments, n: the signal is sent once n points are written, so the run stops
# after point n or n + 1 (the stop check follows each write, the file is seen first);
# tolerance)
LAYER = ["run", "ehl-cylinder-layer", "--set", "mesh=0", "--set", "W=0.5", "--set", "steps=3",
         "--quiet"]
CASES = {
    # a load march (3 loads to 0.5 N/mm), then a speed: the stop falls in the load leg ...
    "ehl-cylinder-layer": (LAYER + ["--set", "speeds=2000"], 1, 1e-6),
    # ... or, with two speeds, after the last load or the first speed (the speed legs resumed)
    "ehl-cylinder-layer-speeds": (LAYER + ["--set", "speeds=2000,4000"], 3, 1e-6),
    # three loads from Hertz states, then two speed marches: stops after the last load
    # or the first speed
    "ehl-ball": (["run", "ehl-ball", "--set", "W=3", "--set", "steps=3", "--set", "mesh=0",
                  "--set", "speeds=2e4,4e4", "--quiet"], 3, 1e-4),
    # large load: thick-film displacement control at U_s, each load marched down to U
    # and the next started from the saved thick-film state: stops after load 2 of 3
    # (the displacement solid with Gauss points: on mesh 0 the mixed solid with the
    # vertex rule does not converge at these loads)
    "ehl-ball-40N": (["run", "ehl-ball", "--set", "W=40", "--set", "theta_l=55", "--set",
                      "U=3e5", "--set", "mesh=0", "--set", "steps=3", "--set", "speeds=6e5",
                      "--set", "formulation=displacement", "--set", "quadrature=gauss",
                      "--quiet"], 1, 1e-4),
    # three variants of one point each (compare=all): stops after the first or second
    # variant, which the resumed run restores complete (nothing left to solve)
    "ehl-ball-compare": (["run", "ehl-ball", "--set", "W=3", "--set", "steps=1", "--set",
                          "mesh=0", "--set", "compare=all", "--quiet"], 1, 1e-4),
    # two strokes of two sealed pressures each: stops at the end of the outstroke or
    # after the first pressure of the instroke (the outstroke restored complete)
    "ehl-oring": (["run", "ehl-oring", "--set", "mesh=2", "--set", "U=1000", "--set",
                   "p_s=0.5,1", "--set", "stroke=both", "--quiet"], 2, 1e-6),
}


def _stopped_then_resumed(out, ranks, sig, case):
    args, n_stop = CASES[case][:2]
    log = [] if case == "ehl-cylinder-layer" else None
    _, resumed, n = stop_then_resume(out, ranks, sig, args, n_stop, log=log)
    assert n in (n_stop, n_stop + 1)
    if log:   # the resumed run's progress bar counts the restored loads: ends at 3/3
        counts = re.findall(r"(\d+)/(\d+) \[", log[0])
        assert counts and counts[-1] == ("3", "3"), log[0][-300:]
    return resumed, n


def _variant(name, keys):
    """The sweep variant (a key of series_points) of the VTX series ``name``."""
    for k in keys:
        if name.startswith((k + "_", k + "stroke_")):
            return k
    assert len(keys) == 1, name
    return next(iter(keys))


def _numbers(x):
    """The numbers of a result (a number, or nested lists of numbers), flat."""
    return np.asarray(x, dtype=float).ravel()


MPIEXEC = pytest.mark.mpiexec   # starts mpiexec itself: run outside pytest-xdist


@pytest.mark.parametrize("case,ranks,sig", [
    ("ehl-cylinder-layer", 1, signal.SIGTERM),
    # slow (13 s): the ball's sweep journal resumes in the default run by the
    # three-variant sweep below (1 rank) and at 40 N on 2 ranks
    pytest.param("ehl-ball", 1, signal.SIGTERM, marks=pytest.mark.slow),
    ("ehl-ball-compare", 1, signal.SIGTERM),
    pytest.param("ehl-cylinder-layer-speeds", 1, signal.SIGTERM, marks=pytest.mark.slow),
    pytest.param("ehl-ball-40N", 2, signal.SIGINT, marks=MPIEXEC),
    # slow (55 s): the journal of strokes × sealed pressures; the journal itself is
    # covered in the default run by the cylinder-layer and ball sweeps above
    pytest.param("ehl-oring", 1, signal.SIGTERM, marks=pytest.mark.slow),
])
def test_stopped_sweep_resumes_to_the_same_result(tmp_path, case, ranks, sig):
    if ranks > 1 and not (Path(sys.executable).parent / "mpiexec").exists():
        pytest.skip("no mpiexec next to the interpreter")
    args, _, tol = CASES[case]
    full = subprocess.run(_cli(ranks) + args + ["--out", str(tmp_path / "full")], env=ENV,
                          capture_output=True, text=True, timeout=900)
    assert full.returncode == 0, full.stderr
    a = json.loads((tmp_path / "full" / "summary.json").read_text())
    b, n = _stopped_then_resumed(tmp_path / "stopped", ranks, sig, case)
    total = sum(len(p) for p in a["series_points"].values())
    print(f"{case}, {ranks} rank(s): stopped after point {n} of {total} by {sig.name}")
    assert n < total          # the stop fell inside the sweep
    assert b["status"] == "ok"
    assert b["parameters"] == a["parameters"]
    compared = [k for k in a["results"] if "wall_time" not in k]
    assert b["results"].keys() == a["results"].keys()
    for key in compared:
        try:
            y, x = _numbers(a["results"][key]["value"]), _numbers(b["results"][key]["value"])
        except (TypeError, ValueError):   # names, not numbers
            assert b["results"][key] == a["results"][key], key
            continue
        assert x.shape == y.shape, key
        scale = np.max(np.abs(y[np.isfinite(y)]), initial=0.0)
        np.testing.assert_allclose(x, y, rtol=0, atol=tol * scale, equal_nan=True,
                                   err_msg=key)
    assert b["series_points"].keys() == a["series_points"].keys()
    for name, pts in a["series_points"].items():
        np.testing.assert_allclose(b["series_points"][name], pts, rtol=tol, err_msg=name)
    assert b["newton_iterations"] == a["newton_iterations"]
    # the VTX series: a variant resumed after k points wrote them into <stem>_series.bp
    # before the stop and the others into <stem>_series_from_k.bp; together, all
    points = a["series_points"]
    written = dict.fromkeys(points, 0)
    for path in (tmp_path / "stopped").glob("*displacement_series*.bp"):
        steps = bp4_steps(path)
        assert steps > 0, path.name    # no empty series (a variant with nothing left)
        if "_from_" in path.name:
            assert steps == len(points[_variant(path.name, points)]) - int(
                path.stem.rsplit("_", 1)[1]), path.name
        written[_variant(path.name, points)] += steps
    assert written == {k: len(p) for k, p in points.items()}


def test_a_journal_of_the_earlier_format_is_refused_in_one_line():
    """A sweep checkpoint written before the legs journalled themselves (its position a
    leg number and the case's own keys) is refused where the variant is built, in one
    line that says what to do."""
    from types import SimpleNamespace

    from mpi4py import MPI

    from tribofx.params import InputError
    from tribofx.sweep import SweepVariant

    class EarlierJournal:   # what SweepJournal reads back from such a checkpoint
        def records(self, key, **empty):
            return dict(empty)

        def position(self, key):
            return {"leg": 0, "k": 2, "inner": {"done": 0.1, "history": []}, "scales": {}}

    with pytest.raises(InputError, match="run again without --resume") as err:
        SweepVariant(EarlierJournal(), "finite", None, [], SimpleNamespace(data={}), {},
                     comm=MPI.COMM_SELF)
    assert "\n" not in str(err.value)
