"""A wear run stopped by SIGINT/SIGTERM between steps and resumed gives the uninterrupted result.

The run writes its state and histories into ``--out/checkpoint`` after every
step; a signal stops it after the step in progress (exit status 130, summary
"interrupted", the last converged state written); ``--resume`` continues from
the checkpoint.  Reference: the same run without interruption.  Tolerance: the
restored state is the checkpoint's arrays exactly, so the two runs can differ
only by the Newton stopping tolerance of the steps after the restart (the wear
rows' relative tolerance 1e-7; the ball's force iteration stops at 1e-8 of F);
in practice they agree to the last digit.  Cases: the pin (steady sliding, 2D),
the ball on a flat held at a force (its flat position is part of the state),
the groove of the half-space (monolithic ALE with replicated cross-section
unknowns, on 2 ranks), the reciprocating pin and block (two worn bodies,
fast-time cycles).
"""

import json
import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ENV = dict(os.environ, UCX_TLS="self,sm,tcp", OMP_NUM_THREADS="1")
ARGS = ["run", "wear-pin", "--set", "mesh=0", "--set", "dt=100", "--quiet"]
# case: (arguments, end time T, stop after this many steps, per-step series compared,
# final profile, VTX series stem)
CASES = {
    "wear-pin": (ARGS, 1000.0, 3, ("wear_volume", "max_wear_depth", "contact_radius",
                                   "wear_rate_integral"), "final_profile", "displacement"),
    # BDF2 with error control: the previous swept volume, its Δt, the proposed next
    # step and the PI controller's memory (the last accepted estimate) are in the state
    # (per step: from the third step on the steps are neither forced at Δt_min nor
    # capped at 2×, so that the memory shapes the steps after the resume)
    "wear-pin-bdf2": (ARGS + ["--set", "scheme=bdf2", "--set", "tol=1e-5", "--set",
                              "tol_per=step", "--set", "controller=pi"], 1000.0, 3,
                      ("wear_volume", "max_wear_depth", "dt", "error_estimate"),
                      "final_profile", "displacement"),
    # the flat's position (held at the force F/2 by a secant iteration) is in the state
    "wear-ball-flat": (["run", "wear-ball-flat", "--set", "dt=100", "--set", "T=300",
                        "--quiet"], 300.0, 1,
                       ("wear_volume", "max_wear_depth", "approach", "contact_radius"),
                       "final_profile", "displacement"),
    # monolithic ALE with the replicated cross-section unknowns Ψ and ζ (ReducedProblem),
    # BDF2: the line's swept areas and their Δt are in the state (c₁ ≠ 0 from step 2)
    "wear-ball-halfspace": (["run", "wear-ball-halfspace", "--set", "dt=100", "--set",
                             "T=300", "--set", "scheme=bdf2", "--quiet"], 300.0, 1,
                            ("wear_volume", "max_wear_depth", "contact_radius",
                             "averaged_rate"), "final_profile", "displacement"),
    # two worn bodies, fast-time cycles (time-scale separation), Picard iteration
    "wear-reciprocating": (["run", "wear-reciprocating", "--set", "mesh=0", "--set",
                            "cycles=100", "--set", "dt=5", "--set", "fast_steps=8",
                            "--quiet"], 20.0, 1,
                           ("worn_area_pin", "worn_area_block", "dissipated_energy",
                            "drive_work"), "final_profile_pin", "pin"),
    # a transient film: the BDF2 histories (content at the quadrature points, u, the
    # trace) and the time weights are in the state; the body held by the film alone
    "ehl-squeeze": (["run", "ehl-squeeze", "--set", "control=load", "--set", "F=0.5",
                     "--set", "E1=10", "--set", "nu1=0.45", "--set", "T=5e-3", "--set",
                     "dt=5e-4", "--quiet"], 5e-3, 3,
                    ("h_center", "h_min", "p_center", "approach"), "final_film",
                    "displacement"),
    # the O-ring over a stroke: the film's histories, the rod speed, the air end's
    # supply and its outstroke record (the stepper's history), the mounted housing
    "ehl-oring-cycle": (["run", "ehl-oring", "--set", "stroke=cycle", "--set", "mesh=2",
                         "--set", "arc_refine=0",
                         "--set", "cycles=0.2", "--set", "cycle_steps=40", "--quiet"], 0.02,
                        2, ("h_min", "flux_air", "content", "supply"), "final_film",
                        "displacement"),
}


def _cli(ranks):
    cli = [sys.executable, "-m", "tribofx.cli"]
    if ranks > 1:
        return [str(Path(sys.executable).parent / "mpiexec"), "-n", str(ranks)] + cli
    return cli


def checkpoint_steps(out):
    """The number of steps (points) written into ``out/checkpoint`` so far (0: none)."""
    try:
        return json.loads((out / "checkpoint" / "state.json").read_text())["steps"]
    except (OSError, ValueError, KeyError):
        return 0


def stop_then_resume(out, ranks, sig, args, n_stop, log=None):
    """Run ``args`` into ``out``, send ``sig`` once n_stop steps are checkpointed, resume.

    Checks the stop (exit status 130, the message, the summary's status); returns
    the interrupted run's summary, the resumed run's and the steps checkpointed
    at the stop.  ``log``: a list; the resumed run then runs without ``--quiet``
    and its standard error (the progress bar) is appended to it.
    """
    p = subprocess.Popen(_cli(ranks) + args + ["--out", str(out)], env=ENV,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    t0 = time.time()
    while checkpoint_steps(out) < n_stop and p.poll() is None and time.time() - t0 < 600:
        time.sleep(0.05)
    p.send_signal(sig)
    _, err = p.communicate(timeout=600)
    assert p.returncode == 130, err
    assert "interrupted" in err and "--resume" in err
    stopped = json.loads((out / "summary.json").read_text())
    assert stopped["status"].startswith("interrupted")
    steps = checkpoint_steps(out)
    again = args if log is None else [a for a in args if a != "--quiet"]
    r = subprocess.run(_cli(ranks) + again + ["--out", str(out), "--resume"], env=ENV,
                       capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stderr
    if log is not None:
        log.append(r.stderr)
    return stopped, json.loads((out / "summary.json").read_text()), steps


def _interrupted_then_resumed(out, ranks, sig, case):
    args, T, n_stop = CASES[case][:3]
    log = [] if case == "wear-pin" and ranks == 1 else None
    s, resumed, _ = stop_then_resume(out, ranks, sig, args, n_stop, log=log)
    if log:   # the resumed run's bar counts the restored steps too: it ends at 10/10
        counts = re.findall(r"(\d+)/(\d+) \[", log[0])
        assert counts and counts[-1] == ("10", "10"), log[0][-300:]
    t_stop = s["results"]["time"]["value"][-1]
    assert 0 < t_stop < T
    assert (out / f"{CASES[case][5]}.bp").exists()    # the last converged state
    return resumed, t_stop


# serial: SIGTERM (a batch system's kill); 2 ranks: SIGINT to mpiexec (Ctrl-C), which
# hydra forwards to the ranks (it turns a SIGTERM of its own into a hard kill of the ranks)
MPIEXEC = pytest.mark.mpiexec   # starts mpiexec itself: run outside pytest-xdist


@pytest.mark.parametrize("case,ranks,sig", [
    # slow (9 s): wear-pin resumes in the default run on 2 ranks and, with its BDF2
    # history, serially (below)
    pytest.param("wear-pin", 1, signal.SIGTERM, marks=pytest.mark.slow),
    ("wear-pin-bdf2", 1, signal.SIGTERM),
    pytest.param("wear-pin", 2, signal.SIGINT, marks=MPIEXEC),
    # slow (26 s): the 3D wear under force control resumes on 2 ranks below (halfspace)
    pytest.param("wear-ball-flat", 1, signal.SIGTERM, marks=pytest.mark.slow),
    pytest.param("wear-ball-halfspace", 2, signal.SIGINT, marks=MPIEXEC),
    ("wear-reciprocating", 1, signal.SIGTERM),
    ("ehl-squeeze", 1, signal.SIGTERM),
    pytest.param("ehl-oring-cycle", 1, signal.SIGTERM, marks=pytest.mark.slow)])
def test_interrupted_run_resumes_to_the_same_result(tmp_path, case, ranks, sig):
    if ranks > 1 and not (Path(sys.executable).parent / "mpiexec").exists():
        pytest.skip("no mpiexec next to the interpreter")
    args, T, _, keys, profile, stem = CASES[case]
    full = subprocess.run(_cli(ranks) + args + ["--out", str(tmp_path / "full")], env=ENV,
                          capture_output=True, text=True, timeout=600)
    assert full.returncode == 0, full.stderr
    a = json.loads((tmp_path / "full" / "summary.json").read_text())
    b, t_stop = _interrupted_then_resumed(tmp_path / "stopped", ranks, sig, case)
    print(f"{case}, {ranks} rank(s): stopped at t = {t_stop} s by {sig.name}, resumed")
    ra, rb = a["results"], b["results"]
    assert rb["time"]["value"] == ra["time"]["value"]
    assert rb["time"]["value"][-1] == pytest.approx(T)
    for key in keys:
        for x, y in zip(rb[key]["value"], ra[key]["value"], strict=True):
            if y is None:            # e.g. the drive work before the first cycle
                assert x is None, key
                continue
            assert abs(x - y) <= 1e-7 * max(abs(y), 1e-12), key
    for x, y in zip(rb[profile]["value"], ra[profile]["value"], strict=True):
        assert max(abs(p - q) for p, q in zip(x, y)) <= 1e-7
    assert b["newton_iterations"] == a["newton_iterations"]
    # the resumed run's VTX series starts where the interrupted one stopped
    assert (tmp_path / "stopped" / f"{stem}_series_from_t{t_stop:g}.bp").exists()


def test_resume_without_checkpoint_is_bad_input(tmp_path):
    r = subprocess.run(_cli(1) + ARGS + ["--out", str(tmp_path / "none"), "--resume"],
                       env=ENV, capture_output=True, text=True, timeout=300)
    assert r.returncode == 2
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and "nothing to resume" in lines[0]
    r = subprocess.run(_cli(1) + ["run", "hertz", "--resume", "--out", str(tmp_path / "h")],
                       env=ENV, capture_output=True, text=True, timeout=300)
    assert r.returncode == 2 and "cannot be resumed" in r.stderr
