"""Every demo is also a test: each runs in its fast mode (``--quick``), serially and on 2 ranks.

A demo ends with its own checks against references (asserts); it fails here when
it raises or exits non-zero.  Demos written in the literate style take
``--quick`` (small meshes, few steps); the list is every ``demos/demo_*.py``
that declares the flag.
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

DEMOS = sorted(p for p in (Path(__file__).parents[1] / "demos").glob("demo_*.py")
               if '"--quick"' in p.read_text())
MPIEXEC = Path(sys.executable).with_name("mpiexec")


def _run(cmd, tmp_path):
    env = dict(os.environ, UCX_TLS="self,sm,tcp", OMP_NUM_THREADS="1", MPLBACKEND="Agg")
    p = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=1800)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    return p.stdout


@pytest.mark.parametrize("demo", DEMOS, ids=lambda p: p.stem)
def test_demo_serial(demo, tmp_path):
    out = _run([sys.executable, str(demo), "--quick", "--out", str(tmp_path / "out")],
               tmp_path)
    assert "all checks passed" in out


@pytest.mark.parametrize("demo", DEMOS, ids=lambda p: p.stem)
def test_demo_two_ranks(demo, tmp_path):
    if os.environ.get("PMI_RANK") or os.environ.get("OMPI_COMM_WORLD_RANK"):
        pytest.skip("already under mpiexec")
    out = _run([str(MPIEXEC), "-n", "2", sys.executable, str(demo), "--quick", "--out",
                str(tmp_path / "out")], tmp_path)
    assert "all checks passed" in out
