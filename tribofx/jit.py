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

Each compile is a CFFI build through setuptools, whose ``Distribution`` looks up
its plugins (``importlib.metadata.entry_points``) seven times per module: each
lookup reads the entry points of every installed distribution, 11 ms here, 75 ms
of the ≈ 0.25 s that a small form takes from an empty cache, about 150 s of
processor time over the 2,100 modules of the test command.  The installed
distributions do not change while a process runs, so :func:`read_plugins_once`
lets setuptools read each group of entry points once per process.

Most of gcc's time on a small module is Python's headers: CFFI's wrapper includes
``Python.h`` (with ``Py_LIMITED_API``), 70 of the 80 ms that gcc takes to compile a
typical form's module.  :func:`compiler_warnings` therefore adds ``-include`` of a
prelude header (``pyconfig.h``, ``Py_LIMITED_API`` as CFFI sets it, ``Python.h``
and the C headers FFCx's code includes) that :func:`prelude` writes, with its
precompiled form (``.gch``), once per JIT cache directory.  gcc reads the
precompiled header in a few milliseconds where it is valid (same compiler and
flags) and otherwise the header itself, so a stale or missing ``.gch`` only costs
time; the header's include guards make the wrapper's own ``#include`` a no-op,
and the object code is the same (measured: identical ``objdump -d``).

FFCx hashes ``cffi_extra_compile_args`` into the name of the cached module, so
quiet compiles and those with warnings (``-v``) have separate entries in the
JIT cache (each compiled once).  Every rank of a run must make the same choice
(the CLI does).  ``jit_options`` passed to a compile, or a
``dolfinx_jit_options.json`` that sets ``cffi_extra_compile_args``, take
priority over this default (see :func:`dolfinx.jit.ffcx_jit`).
"""

import hashlib
import importlib.metadata
import os
import subprocess
import sys
import sysconfig
import types
from pathlib import Path
from typing import Any

import dolfinx.jit

__all__ = ["OPTIMISATION", "PRELUDE", "QUIET_ARGS", "compiler_warnings", "prelude",
           "read_plugins_once"]

QUIET_ARGS: list[str] = ["-w"]
"""C compiler arguments appended to the JIT's arguments to silence its warnings."""

OPTIMISATION: str = "-O1"
"""gcc's optimisation level for the JIT, in place of DOLFINx's ``-O2`` (see above)."""

_OPTIONS: dict[str, Any] = dolfinx.jit.DOLFINX_DEFAULT_JIT_OPTIONS
_DEFAULT_ARGS: list[str] = [OPTIMISATION if a.startswith("-O") else a
                            for a in _OPTIONS["cffi_extra_compile_args"][0]]


PRELUDE: str = """\
/* tribofx.jit: the headers of every JIT module, precompiled (see tribofx/jit.py) */
#include <pyconfig.h>
#if !defined(Py_DEBUG) && !defined(Py_TRACE_REFS) && !defined(Py_REF_DEBUG) \\
    && !defined(Py_GIL_DISABLED) && !defined(Py_LIMITED_API)
#  define Py_LIMITED_API
#endif
#include <Python.h>
#include <complex.h>
#include <math.h>
#include <stdalign.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
"""
"""The prelude header that every JIT compile includes first (``-include``), precompiled."""


def _compile_command(args: list[str]) -> list[str]:
    """Return the compile command of CFFI's builds (distutils' compiler, FFCx's includes, args)."""
    import distutils.ccompiler  # setuptools' distutils, as CFFI's builds use it
    import distutils.sysconfig
    import ffcx.codegeneration

    compiler = distutils.ccompiler.new_compiler()
    distutils.sysconfig.customize_compiler(compiler)  # type: ignore[no-untyped-call]
    includes = [os.path.dirname(ffcx.codegeneration.__file__), os.path.join(sys.prefix, "include"),
                sysconfig.get_paths()["include"]]
    return [*compiler.compiler_so, *(f"-I{d}" for d in includes), "-std=c17", *args]


def prelude(args: list[str]) -> Path:
    """Return the prelude header for compiles with ``args``, written and precompiled if missing.

    The header and its ``.gch`` live in ``<JIT cache>/tribofx-prelude-<key>/``, the key
    a hash of :data:`PRELUDE`, the Python and the compile command.  Each is written
    under a temporary name and renamed, so that processes starting together
    (ranks, test workers) never read a partial file.  When the precompile fails
    (another compiler), the header alone is used.
    """
    command = _compile_command(args)
    key = hashlib.sha1("\0".join([PRELUDE, sys.version, *command]).encode()).hexdigest()[:16]
    folder = Path(dolfinx.jit.get_options()["cache_dir"]) / f"tribofx-prelude-{key}"
    header = folder / "tribofx_jit_prelude.h"
    pch = folder / "tribofx_jit_prelude.h.gch"
    if header.exists() and pch.exists():
        return header
    folder.mkdir(parents=True, exist_ok=True)
    part = f".{os.getpid()}.part"
    if not header.exists():
        Path(str(header) + part).write_text(PRELUDE)
        os.replace(str(header) + part, header)
    if not pch.exists():
        out = str(pch) + part
        done = subprocess.run([*command, "-x", "c-header", str(header), "-o", out],
                              capture_output=True)
        if done.returncode == 0:
            os.replace(out, pch)
        elif os.path.exists(out):
            os.remove(out)
    return header


def compiler_warnings(show: bool) -> None:
    """Show (the arguments at :data:`OPTIMISATION`) or hide (plus :data:`QUIET_ARGS`) warnings.

    Sets the process-wide default of ``cffi_extra_compile_args`` in
    :data:`dolfinx.jit.DOLFINX_DEFAULT_JIT_OPTIONS`, with the :func:`prelude`
    included first; compiles already in the JIT cache are not repeated.
    """
    args = _DEFAULT_ARGS if show else _DEFAULT_ARGS + QUIET_ARGS
    args = [*args, "-include", str(prelude(args))]
    _OPTIONS["cffi_extra_compile_args"] = (list(args), _OPTIONS["cffi_extra_compile_args"][1])


class _EntryPointsOnce:
    """:mod:`importlib.metadata` whose ``entry_points(**selection)`` is read once per selection."""

    def __init__(self, metadata: types.ModuleType) -> None:
        self._metadata = metadata
        self._read: dict[tuple[tuple[str, Any], ...], Any] = {}

    def entry_points(self, **selection: Any) -> Any:
        """Return ``importlib.metadata.entry_points(**selection)``, read on the first call."""
        key = tuple(sorted(selection.items()))
        if key not in self._read:
            self._read[key] = self._metadata.entry_points(**selection)
        return self._read[key]

    def __getattr__(self, name: str) -> Any:
        return getattr(self._metadata, name)


def read_plugins_once() -> None:
    """Let setuptools (the JIT's CFFI builds) read each group of entry points once per process.

    Replaces ``setuptools.dist.metadata`` (the :mod:`importlib.metadata` that
    setuptools' ``Distribution`` reads its plugins from) by a proxy that keeps
    what ``entry_points`` returned; nothing else in the process is affected.
    A setuptools that reads its plugins elsewhere is left as it is.
    """
    import setuptools.dist

    if getattr(setuptools.dist, "metadata", None) is importlib.metadata:
        setuptools.dist.metadata = _EntryPointsOnce(importlib.metadata)  # type: ignore[assignment]
