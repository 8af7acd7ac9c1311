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
    (["run", "hertz", "--set", "dim=two"], "expects dimension"),
    (["run", "hertz", "--set", "dim=4"], "must be one of"),
    (["run", "hertz", "--set", "obstacle=cube"], "must be one of"),
    (["run", "hertz", "--set", "friction=-0.1"], "must be >= 0"),
    (["run", "hertz", "--set", "load=1e6"], "load too large"),
    (["run", "hertz", "--set", "E"], "KEY=VALUE"),
    (["run", "hertz", "--set", "E=inf"], "must be finite"),
    (["run", "hertz", "--set", "R=nan"], "must be finite"),
    (["run", "hertz", "--set", "load=1e-30"], "load too small"),
    (["run", "contact-patch", "--set", "mesh_ratio=0"], "needs at least 2"),
    (["run", "wear-ball-flat", "--set", "h_contact=0.1", "--set", "mesh_file=b.msh"],
     "h_contact sets the built mesh"),
    (["run", "ehl-squeeze", "--set", "cavitation=jfo", "--set", "V=-1", "--set",
      "dim=axisymmetric"], "cavitation=jfo is built for dim=2 and dim=3"),
    (["run", "ehl-ball", "--set", "cavitation=jfo", "--set", "compare=all"],
     "cavitation=jfo is built for the built ball"),
    (["run", "ehl-ball", "--set", "supply=0.01"], "supply (a starved inlet) needs"),
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


def test_run_file_repeats_a_run_exactly(tmp_path):
    """A TOML run file gives the run of its --set twin; summary.json holds every parameter.

    The parameters recorded by the first run, written back as a run file, repeat
    it: the same results to the last digit (same code, same input, one process).
    """
    first = tmp_path / "first"
    p = _run("run", "reynolds-slider", "--set", "K=2", "--set", "mesh=40", "--out", str(first),
             "--quiet")
    assert p.returncode == 0, p.stderr
    s1 = json.loads((first / "summary.json").read_text())
    lines = ['case = "reynolds-slider"', "[parameters]"]
    for k, v in s1["parameters"].items():
        val = v["value"]
        lines.append(f"{k} = {json.dumps(val) if not isinstance(val, bool) else str(val).lower()}")
    run_file = tmp_path / "slider.toml"
    run_file.write_text("\n".join(lines) + "\n")
    second = tmp_path / "second"
    p = _run("run", str(run_file), "--out", str(second), "--quiet")
    assert p.returncode == 0, p.stderr
    s2 = json.loads((second / "summary.json").read_text())
    assert s2["parameters"] == s1["parameters"]
    assert {k: v["value"] for k, v in s2["results"].items()} == \
        {k: v["value"] for k, v in s1["results"].items()}
    # --set still overrides the file
    p = _run("run", str(run_file), "--set", "K=1", "--out", str(tmp_path / "third"), "--quiet")
    s3 = json.loads((tmp_path / "third" / "summary.json").read_text())
    assert p.returncode == 0 and s3["parameters"]["K"]["value"] == 1.0


@pytest.mark.parametrize("content,fragment", [
    (None, "cannot read run file"),
    ("case = \"hertz\"\n[parameters\n", "not valid TOML"),
    ("[parameters]\nE = 5\n", "needs a line case"),
    ("case = \"hertz\"\nfoo = 1\n", "only 'case' and a [parameters] table"),
    ("case = \"hertz\"\n[parameters]\nE = -1\n", "'E' must be > 0"),
])
def test_bad_run_file(tmp_path, content, fragment):
    path = tmp_path / "run.toml"
    if content is not None:
        path.write_text(content)
    p = _run("run", str(path), "--out", str(tmp_path / "out"))
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], p.stderr
    assert not (tmp_path / "out").exists()
