"""Run a named case: parameters → solve → ``summary.json``, plots and VTX in an output folder."""

from pathlib import Path

from mpi4py import MPI

from .cases import get_case
from .output import RunRecord, write_vtx
from .params import resolve
from .problem import NewtonDivergence

__all__ = ["run_case"]


def _progress_bar(total, name="run"):
    from tqdm import tqdm

    return tqdm(total=total, desc=name, unit="step")


def run_case(name, overrides=None, out="results", comm=MPI.COMM_WORLD, progress=True,
             verbose=False):
    """Run case ``name`` with ``overrides`` {key: text}; returns the summary dict.

    Raises :class:`tribofx.params.InputError` for bad input.  A Newton failure
    that step cutting cannot cure ends the run with status "failed: …"; the last
    converged state is still written.

    A case is a class with ``name``, ``doc``, ``params`` (:class:`Param` tuple) and
    the static/class methods ``validate(values)``, ``run(values, record, progress,
    verbose)`` (returns the problem object; on failure it raises
    :class:`NewtonDivergence` with the problem, restored to its last converged
    state, as attribute ``problem``), ``vtx_fields(problem)`` ({file stem:
    [Functions on one mesh]}) and ``plot(profile, outdir)`` (rank 0; ``profile``
    is what ``run`` stored in ``record.profile``).  ``run`` advances ``progress``
    once per load/time step; the bar length is ``values["steps"]`` when present.
    """
    case = get_case(name)
    values = resolve(case.params, overrides or {})
    case.validate(values)
    units = {p.name: p.unit for p in case.params}
    out = Path(out)
    record = RunRecord(name, values, units, out, comm)
    record.profile = None
    bar = _progress_bar(values.get("steps", 1), name) if progress and comm.rank == 0 else None
    status = "ok"
    prob = None
    try:
        prob = case.run(values, record, progress=bar, verbose=verbose)
    except NewtonDivergence as err:
        status = f"failed: {err}"
        prob = getattr(err, "problem", None)
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
