"""Command line: listing, bad input (exit 2, one-line message), and a real run."""

import json
import os
import subprocess
import sys

import pytest

ENV = dict(os.environ, UCX_TLS="self,sm,tcp")
CLI = [sys.executable, "-m", "tribofx.cli"]


def _run(*args):
    return subprocess.run(CLI + list(args), capture_output=True, text=True, env=ENV,
                          timeout=600)


def test_list():
    p = _run("list")
    assert p.returncode == 0
    assert "hertz" in p.stdout and "MPa" in p.stdout


@pytest.mark.parametrize("args,fragment", [
    (["run", "no-such-case"], "unknown case"),
    (["run", "hertz", "--set", "colour=red"], "unknown parameter"),
    (["run", "hertz", "--set", "E=-1"], "'E' must be > 0"),
    (["run", "hertz", "--set", "E=0"], "'E' must be > 0"),
    (["run", "hertz", "--set", "nu=0.5"], "'nu' must be < 0.5"),
    (["run", "hertz", "--set", "dim=two"], "expects int"),
    (["run", "hertz", "--set", "dim=4"], "must be one of"),
    (["run", "hertz", "--set", "obstacle=cube"], "must be one of"),
    (["run", "hertz", "--set", "friction=-0.1"], "must be >= 0"),
    (["run", "hertz", "--set", "load=1e6"], "load too large"),
    (["run", "hertz", "--set", "E"], "KEY=VALUE"),
    (["run", "hertz", "--set", "E=inf"], "must be finite"),
    (["run", "hertz", "--set", "R=nan"], "must be finite"),
    (["run", "hertz", "--set", "load=1e-30"], "load too small"),
    (["frobnicate"], "invalid choice"),
])
def test_bad_input(args, fragment):
    p = _run(*args)
    assert p.returncode == 2
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, p.stderr
    assert fragment in lines[0]
    assert "Traceback" not in p.stderr


def test_run_writes_outputs(tmp_path):
    out = tmp_path / "run"
    p = _run("run", "hertz", "--set", "mesh=0", "--set", "load=0.05", "--out", str(out),
             "--quiet")
    assert p.returncode == 0, p.stderr
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "ok" and s["mpi_size"] == 1 and s["num_dofs"] > 0
    assert s["parameters"]["E"] == {"value": 10.0, "unit": "MPa"}
    assert s["results"]["p_max"]["unit"] == "MPa"
    assert s["newton_iterations"] and s["dolfinx_version"].startswith("0.11")
    assert (out / "pressure.png").stat().st_size > 0
    assert (out / "displacement.bp").is_dir() and (out / "contact.bp").is_dir()
