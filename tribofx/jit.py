"""C compiler warnings of the JIT: off by default, on with ``tribofx run -v``.

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

FFCx hashes ``cffi_extra_compile_args`` into the name of the cached module, so
quiet compiles and those with warnings (``-v``) have separate entries in the
JIT cache (each compiled once).  Every rank of a run must make the same choice
(the CLI does).  ``jit_options`` passed to a compile, or a
``dolfinx_jit_options.json`` that sets ``cffi_extra_compile_args``, take
priority over this default (see :func:`dolfinx.jit.ffcx_jit`).
"""

from typing import Any

import dolfinx.jit

__all__ = ["QUIET_ARGS", "compiler_warnings"]

QUIET_ARGS: list[str] = ["-w"]
"""C compiler arguments appended to DOLFINx's defaults to silence its warnings."""

_OPTIONS: dict[str, Any] = dolfinx.jit.DOLFINX_DEFAULT_JIT_OPTIONS
_DEFAULT_ARGS: list[str] = list(_OPTIONS["cffi_extra_compile_args"][0])


def compiler_warnings(show: bool) -> None:
    """Show (DOLFINx's default arguments) or hide (plus :data:`QUIET_ARGS`) the JIT's C warnings.

    Sets the process-wide default of ``cffi_extra_compile_args`` in
    :data:`dolfinx.jit.DOLFINX_DEFAULT_JIT_OPTIONS`; compiles already in the
    JIT cache are not repeated.
    """
    args = _DEFAULT_ARGS if show else _DEFAULT_ARGS + QUIET_ARGS
    _OPTIONS["cffi_extra_compile_args"] = (list(args), _OPTIONS["cffi_extra_compile_args"][1])
