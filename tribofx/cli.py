"""Command line: ``tribofx list`` and ``tribofx run CASE [--set k=v ...] [--out DIR]``."""

from __future__ import annotations

import argparse
import sys
from typing import TYPE_CHECKING, NoReturn

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = ["main"]


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:
        sys.stderr.write(f"tribofx: error: {message}\n")
        sys.exit(2)


def _list() -> None:
    from .cases import CASES
    from .params import declared
    from .runner import RunOptions

    print("every case:")
    for p in declared(RunOptions):
        extra = f" one of {list(p.choices)}" if p.choices else ""
        print(f"    {p.name} = {p.default!r} [{p.unit}]  {p.doc}{extra}")
    for name, case in sorted(CASES.items()):
        print(f"{name}: {case.doc}")
        for p in declared(case.Params):
            extra = f" one of {list(p.choices)}" if p.choices else ""
            print(f"    {p.name} = {p.default!r} [{p.unit}]  {p.doc}{extra}")


def _run_file(path: str) -> tuple[str, dict[str, str]]:
    """Case name and parameters {key: text} of a TOML run file."""
    import tomllib

    from .params import InputError

    try:
        with open(path, "rb") as f:
            data = tomllib.load(f)
    except OSError as err:
        raise InputError(f"cannot read run file {path!r}: {err.strerror}") from None
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"run file {path!r} is not valid TOML: {err}") from None
    case = data.get("case")
    if not isinstance(case, str):
        raise InputError(f"run file {path!r} needs a line case = \"<case name>\"")
    params = data.get("parameters", {})
    if not isinstance(params, dict) or set(data) - {"case", "parameters"}:
        raise InputError(f"run file {path!r}: only 'case' and a [parameters] table are allowed")

    def text(v: object) -> str:
        if isinstance(v, bool):
            return str(v).lower()
        if isinstance(v, list):   # e.g. p_s = [1, 5]: the comma-separated form of --set
            return ",".join(text(x) for x in v)
        return str(v)

    return case, {k: text(v) for k, v in params.items()}


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``tribofx`` command; returns the exit status."""
    parser = _Parser(prog="tribofx", description=__doc__)
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("list", help="list cases and their parameters")
    run = sub.add_parser("run", help="run a case")
    run.add_argument("case", help="case name, or a run file FILE.toml (case = \"…\" and a "
                     "[parameters] table; --set overrides it)")
    run.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    run.add_argument("--petsc-option", action="append", default=[], metavar="KEY[=VALUE]",
                     help="PETSc option for every problem of the run (e.g. "
                     "ksp_monitor, mat_mumps_icntl_35=1); a key starting with tribofx_ "
                     "is set as given")
    run.add_argument("--out", default=None)
    run.add_argument("--quiet", action="store_true", help="no progress bar")
    run.add_argument("--resume", action="store_true",
                     help="continue a stopped run from the checkpoint in --out (wear cases)")
    run.add_argument("-v", "--verbose", action="store_true",
                     help="print the Newton residuals of every block, and the C "
                     "compiler's warnings of JIT compiles")
    args = parser.parse_args(argv)
    if args.command == "list":
        _list()
        return 0
    from .params import InputError

    overrides: dict[str, str] = {}
    if args.case.endswith(".toml"):
        try:
            args.case, overrides = _run_file(args.case)
        except InputError as err:
            sys.stderr.write(f"tribofx: error: {err}\n")
            return 2
    for item in args.set:
        key, sep, value = item.partition("=")
        if not sep or not key:
            sys.stderr.write(f"tribofx: error: --set expects KEY=VALUE, got {item!r}\n")
            return 2
        overrides[key.strip()] = value.strip()
    petsc = {}
    for item in args.petsc_option:
        key, sep, value = item.partition("=")
        key = key.strip().lstrip("-")
        if not key or (sep and not value.strip()) or any(c.isspace() for c in key):
            sys.stderr.write(f"tribofx: error: --petsc-option expects KEY or KEY=VALUE, "
                             f"got {item!r}\n")
            return 2
        petsc[key] = value.strip() if sep else None
    try:
        import dolfinx_solver  # noqa: F401  (must precede dolfinx/petsc4py)

        from .jit import compiler_warnings
        from .runner import run_case

        compiler_warnings(show=args.verbose)

        summary = run_case(args.case, overrides, args.out or f"results/{args.case}",
                           progress=not args.quiet, verbose=args.verbose,
                           petsc_options=petsc, resume=args.resume)
    except InputError as err:
        from mpi4py import MPI

        if MPI.COMM_WORLD.rank == 0:  # every rank detects it; one line in all
            sys.stderr.write(f"tribofx: error: {err}\n")
        return 2
    from mpi4py import MPI

    root = MPI.COMM_WORLD.rank == 0
    for message in summary.get("warnings", []) if root else []:
        sys.stderr.write(f"tribofx: warning: {message}\n")
    if summary["status"].startswith("interrupted"):
        if root:
            sys.stderr.write(f"tribofx: run {summary['status']}; continue it with --resume\n")
        return 130
    if not summary["status"].startswith("ok"):
        if root:
            sys.stderr.write(f"tribofx: run {summary['status']}\n")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
