"""Quiet runs: no C compiler warnings of the JIT on stderr, unless ``tribofx run -v``.

Each run is a fresh process with an empty JIT cache (``XDG_CACHE_HOME``, read
by ``dolfinx.jit``) and no user/local ``dolfinx_jit_options.json``, so every
form really is compiled.  No fast case makes gcc warn, so after ``tribofx run
reynolds-slider`` (through :func:`tribofx.cli.main`) the same process compiles
a form that does: an integrand that FFCx folds to zero leaves the unused
variable ``interval_reference_cell_volume`` (as a Jacobian block of
``ehl-oring`` does).
"""

import os
import subprocess
import sys

import pytest

SCRIPT = """
import sys

import tribofx.cli

status = tribofx.cli.main(sys.argv[1:])
assert status == 0, status
print("run done", flush=True)

import ufl
from dolfinx import fem, mesh
from mpi4py import MPI

m = mesh.create_unit_interval(MPI.COMM_SELF, 2)
V = fem.functionspace(m, ("Lagrange", 1))
u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
fem.form((-1 * u + u) / ufl.CellDiameter(m) * v * ufl.dx)
print("compiled", flush=True)
"""


def _run(tmp_path, *flags):
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"),
               XDG_CONFIG_HOME=str(tmp_path / "config"), UCX_TLS="self,sm,tcp",
               OMP_NUM_THREADS="1")
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT, "run", "reynolds-slider", "--quiet",
         "--out", str(tmp_path / "out"), *flags],
        cwd=tmp_path, env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert "compiled" in out.stdout
    assert list((tmp_path / "cache" / "fenics").glob("*.so")), "nothing was compiled"
    return [line for line in out.stderr.splitlines() if "warning:" in line]


@pytest.mark.parametrize("verbose", [False, True], ids=["default", "verbose"])
def test_jit_compiler_warnings_only_with_verbose(tmp_path, verbose):
    warnings = _run(tmp_path, *(["-v"] if verbose else []))
    if verbose:
        assert any("interval_reference_cell_volume" in w for w in warnings), warnings
    else:
        assert not warnings, "\n".join(warnings)


PCH_SCRIPT = """
import tribofx  # the JIT's arguments, with the prelude written and precompiled

import ufl
from dolfinx import fem, mesh
from mpi4py import MPI

m = mesh.create_unit_square(MPI.COMM_SELF, 2, 2)
V = fem.functionspace(m, ("Lagrange", 1))
u = fem.Function(V)
fem.form(ufl.sin(u) * ufl.dx, jit_options={"cffi_verbose": True})
"""


def test_jit_compiles_read_the_precompiled_prelude(tmp_path):
    """The compile command CFFI really runs uses the prelude's precompiled header.

    The ``.gch`` only counts where gcc finds it valid for the command's flags (else
    gcc silently parses the headers again: right, but 70 of every 80 ms of a small
    module's compile come back, tribofx.jit).  The command is the one CFFI printed
    (``cffi_verbose``) for a fresh form, run again with ``-H``: gcc marks a
    precompiled header it uses with ``!``.
    """
    env = dict(os.environ, XDG_CACHE_HOME=str(tmp_path / "cache"),
               XDG_CONFIG_HOME=str(tmp_path / "config"), UCX_TLS="self,sm,tcp",
               OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", PCH_SCRIPT], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    commands = [line.split() for line in out.stdout.splitlines() if " -c " in line]
    assert len(commands) == 1, out.stdout
    command = commands[0]
    assert "-include" in command, command
    header = command[command.index("-include") + 1]
    cache = next((tmp_path / "cache" / "fenics").glob("libffcx_forms_*.c")).parent
    command[command.index("-o") + 1] = str(tmp_path / "again.o")
    shown = subprocess.run([*command, "-H"], cwd=cache, capture_output=True, text=True,
                           timeout=60)
    assert shown.returncode == 0, shown.stderr
    assert f"! {header}.gch" in shown.stderr.splitlines()[0], shown.stderr[:400]
