"""The JIT's C compiler arguments: ``-O1``, and warnings off unless ``tribofx run -v``.

DOLFINx compiles every form and expression (``fem.form``, ``fem.Expression``,
``fem.petsc.NonlinearProblem``, …) with FFCx and CFFI, through
:func:`dolfinx.jit.ffcx_jit`.  gcc runs with Python's ``-Wall`` and writes its
warnings about the generated C straight to stderr (``cffi_verbose`` does not
hide them), e.g. "unused variable 'interval_reference_cell_volume'" for an
integrand that FFCx folds to zero.  They are harmless and not the user's to act
on, so importing :mod:`tribofx` calls :func:`compiler_warnings` once with
``show=False``: ``-w`` is appended to DOLFINx's default
``cffi_extra_compile_args`` (``["-O2", "-g0"]``), for every compile of the
process, also those of code that does not pass ``jit_options`` (the cases, the
demos).  ``-w`` only silences diagnostics: the object code is the same.

The optimisation level is ``-O1`` instead of DOLFINx's ``-O2``: gcc spends less
time on the large generated kernels (the hyperelastic and film Jacobians) and
they run as fast.  Neither level reassociates floating-point operations (no
``-ffast-math``) nor contracts them into FMAs on the x86-64 baseline, so the
kernels compute the same numbers bit for bit.  Measured on the tests of the
O-ring and the ball (2 cores, 31 tests): from an empty JIT cache 195.6 s at
``-O2``, 182.9 s at ``-O1``; with the kernels cached 91.3 s and 88.2 s.  The
whole test command from an empty cache: 1007 s at ``-O2`` (one run), 848 and 900 s at
``-O1`` (two runs; runs of the same code on this kind of machine vary by up to ~15 %).

FFCx hashes ``cffi_extra_compile_args`` into the name of the cached module, so
quiet compiles and those with warnings (``-v``) have separate entries in the
JIT cache (each compiled once).  Every rank of a run must make the same choice
(the CLI does).  ``jit_options`` passed to a compile, or a
``dolfinx_jit_options.json`` that sets ``cffi_extra_compile_args``, take
priority over this default (see :func:`dolfinx.jit.ffcx_jit`).
"""

from typing import Any

import dolfinx.jit

__all__ = ["OPTIMISATION", "QUIET_ARGS", "compiler_warnings"]

QUIET_ARGS: list[str] = ["-w"]
"""C compiler arguments appended to the JIT's arguments to silence its warnings."""

OPTIMISATION: str = "-O1"
"""gcc's optimisation level for the JIT, in place of DOLFINx's ``-O2`` (see above)."""

_OPTIONS: dict[str, Any] = dolfinx.jit.DOLFINX_DEFAULT_JIT_OPTIONS
_DEFAULT_ARGS: list[str] = [OPTIMISATION if a.startswith("-O") else a
                            for a in _OPTIONS["cffi_extra_compile_args"][0]]


def compiler_warnings(show: bool) -> None:
    """Show (the arguments at :data:`OPTIMISATION`) or hide (plus :data:`QUIET_ARGS`) warnings.

    Sets the process-wide default of ``cffi_extra_compile_args`` in
    :data:`dolfinx.jit.DOLFINX_DEFAULT_JIT_OPTIONS`; compiles already in the
    JIT cache are not repeated.
    """
    args = _DEFAULT_ARGS if show else _DEFAULT_ARGS + QUIET_ARGS
    _OPTIONS["cffi_extra_compile_args"] = (list(args), _OPTIONS["cffi_extra_compile_args"][1])
