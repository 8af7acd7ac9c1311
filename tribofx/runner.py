"""Run a named case: parameters → solve → ``summary.json``, plots and VTX in an output folder."""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from mpi4py import MPI

from . import interrupt, solvers, studies
from .cases import get_case
from .output import RunRecord, write_vtx
from .params import CaseParams, InputError, declared, param, resolve
from .reports import RunStop

if TYPE_CHECKING:
    from collections.abc import Mapping

    from tqdm import tqdm

__all__ = ["RunOptions", "run_case"]


@dataclass(frozen=True)
class RunOptions(CaseParams):
    """What every case accepts besides its own parameters (``--set solver=iterative``)."""

    solver: str = param(
        "auto", "-",
        "linear solver: direct (MUMPS LU), lagged (GMRES on the LU of an earlier Newton "
        "matrix), iterative (GMRES, AMG on the bulk, Schur complement of the interface "
        f"unknowns), auto (from {solvers.AUTO_THRESHOLD} unknowns: iterative on 3D "
        "tetrahedral meshes, lagged on others; direct below)", choices=solvers.STRATEGIES)


def _progress_bar(total: int, name: str = "run") -> tqdm:
    from tqdm import tqdm

    return tqdm(total=total, desc=name, unit="step")


def resumable(name: str) -> bool:
    """Whether case ``name`` writes a checkpoint each step and can be resumed (it says so)."""
    return bool(get_case(name).resumable)


def run_case(name: str, overrides: Mapping[str, str] | None = None, out: str | Path = "results",
             comm: MPI.Comm = MPI.COMM_WORLD, progress: bool = True, verbose: bool = False,
             petsc_options: Mapping[str, str | None] | None = None,
             resume: bool = False) -> dict[str, Any]:
    """Run case ``name`` with ``overrides`` {key: text}; returns the summary dict.

    ``petsc_options`` {key: value} go to every problem of the run
    (:func:`tribofx.solvers.run_settings`); they and the linear solver each
    problem used are recorded in the summary.

    Raises :class:`tribofx.params.InputError` for bad input.  A Newton failure
    that step cutting cannot cure ends the run with status "failed: …"; the last
    converged state is still written.

    A resumable case (``resumable = True``; its ``run`` takes ``checkpoint`` and
    ``resume``) writes a checkpoint into ``out/checkpoint`` after every step;
    ``resume=True`` continues from it.  SIGINT/SIGTERM stop such a run after the step in
    progress with status "interrupted: …" and its state written
    (:mod:`tribofx.interrupt`).

    A case is a module of :mod:`tribofx.cases` with ``name``, ``doc``, ``Params``
    (its :class:`~tribofx.params.CaseParams` dataclass), ``resumable`` and the
    functions ``validate(params)``, ``run(params, record, progress, verbose)``
    (returns its model, what its ``build`` assembled; on failure it raises
    :class:`~tribofx.reports.NewtonDivergence`, a :class:`~tribofx.reports.RunStop`,
    with the model, restored to its last converged state, as ``model``),
    ``progress_total(params)``, ``vtx_fields(model)`` ({file stem: [Functions on one
    mesh]}) and ``plot(profile,
    outdir)`` (rank 0; ``profile`` is what ``run`` stored in ``record.profile``).
    ``run`` advances ``progress`` once per load/time step (a slow-time stepper by
    time, in nominal steps of its Δt); the bar length is the case's
    ``progress_total(params)``.
    """
    case = get_case(name)
    if resume and not resumable(name):
        raise InputError(f"case {name!r} cannot be resumed (no per-step checkpoint)")
    overrides = dict(overrides or {})
    common = {p.name for p in declared(RunOptions)}
    options = resolve(RunOptions, {k: overrides.pop(k) for k in common & set(overrides)})
    values = resolve(case.Params, overrides)
    case.validate(values)
    study = studies.study_of(name, values)
    driver = case if study is None else study
    if resume and study is not None:
        raise InputError(f"a study of {name!r} cannot be resumed (no per-step checkpoint)")
    out = Path(out)
    kwargs: dict[str, Any] = {}
    if resumable(name) and study is None:
        kwargs = {"checkpoint": out / "checkpoint", "resume": resume}
        if resume and not (out / "checkpoint" / "state.json").is_file():
            raise InputError(f"nothing to resume: no checkpoint in {out / 'checkpoint'}")
    record = RunRecord(name, {**values.as_dict(), **options.as_dict()},
                       {p.name: p.unit for p in declared(case.Params) + declared(RunOptions)},
                       out, comm)
    record.profile = None
    record.data["petsc_options"] = dict(petsc_options or {})
    show = progress and comm.rank == 0
    bar = _progress_bar(driver.progress_total(values), name) if show else None
    status = "ok"
    prob = None
    try:
        watch = interrupt.watch() if kwargs else contextlib.nullcontext()
        with solvers.run_settings(options.solver, petsc_options) as linear, watch:
            try:
                prob = driver.run(values, record, progress=bar, verbose=verbose, **kwargs)
            finally:
                record.data["linear_solver"] = dict(linear.used)
                fallbacks = linear.failed_krylov()
                if fallbacks:
                    record.data["linear_fallbacks"] = fallbacks
                    n = sum(map(len, fallbacks.values()))
                    record.warn(f"{n} Krylov solves failed and were solved by LU "
                                f"(linear_fallbacks)")
    except RunStop as err:
        kind = "interrupted" if isinstance(err, interrupt.Interrupted) else "failed"
        status = f"{kind}: {err}"
        prob = err.model
    finally:
        if bar is not None:
            bar.close()
    if comm.rank == 0:
        out.mkdir(parents=True, exist_ok=True)
    comm.barrier()
    if prob is not None:
        for name, functions in case.vtx_fields(prob).items():
            write_vtx(comm, out / f"{name}.bp", functions)
    if comm.rank == 0 and record.profile is not None:
        case.plot(record.profile, out)
    return record.write(status)
