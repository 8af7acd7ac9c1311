"""Run a named case: parameters → solve → ``summary.json``, plots and VTX in an output folder."""

from pathlib import Path

from mpi4py import MPI

from .cases import get_case
from .newton import NewtonDivergence
from .output import RunRecord, write_vtx
from .params import resolve

__all__ = ["run_case"]


def run_case(name, overrides=None, out="results", comm=MPI.COMM_WORLD, progress=True,
             verbose=False):
    """Run case ``name`` with ``overrides`` {key: text}; returns the summary dict.

    Raises :class:`tribofx.params.InputError` for bad input.  A Newton failure
    that step cutting cannot cure ends the run with status "failed: …"; the last
    converged state is still written.
    """
    case = get_case(name)
    values = resolve(case.params, overrides or {})
    case.validate(values)
    units = {p.name: p.unit for p in case.params}
    out = Path(out)
    record = RunRecord(name, values, units, out, comm)
    record.profile = None
    bar = None
    if progress and comm.rank == 0:
        from tqdm import tqdm

        bar = tqdm(total=values.get("steps", 1), desc=name, unit="step")
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
        write_vtx(comm, out / "displacement.bp", [prob.u])
        write_vtx(comm, out / "contact.bp", [prob.lam_n])
    if comm.rank == 0 and record.profile is not None:
        from .plots import plot_hertz_pressure

        plot_hertz_pressure(record.profile, out / "pressure.png")
    return record.write(status)
