"""PNG plots of case results (rank 0, matplotlib Agg backend), one module per subject."""

from .common import pyplot
from .contact import plot_hertz_pressure

__all__ = ["plot_hertz_pressure", "pyplot"]
