"""Accumulated wall time of wrapped callables, for the benchmarks' splits of an iteration."""

import time

__all__ = ["Timer"]


class Timer:
    """Accumulated wall time of wrapped callables (``total[name]``, s)."""

    def __init__(self):
        self.total = {}

    def wrap(self, name, fn):
        """Return ``fn`` timed under ``name``."""
        def timed(*args, **kw):
            t0 = time.perf_counter()
            try:
                return fn(*args, **kw)
            finally:
                self.total[name] = self.total.get(name, 0.0) + time.perf_counter() - t0
        return timed
