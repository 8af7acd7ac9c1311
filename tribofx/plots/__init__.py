"""PNG plots of case results (rank 0, matplotlib Agg backend), one module per subject."""

from .common import pyplot
from .contact import plot_hertz_pressure
from .film import (
    plot_ball_film,
    plot_film_profiles,
    plot_friction_vs_speed,
    plot_oring,
    plot_oring_cycle,
    plot_reynolds_cylinder,
    plot_slider,
)
from .groove import plot_groove, plot_pressure_across
from .wear import plot_dt_study, plot_wear_ball, plot_wear_pin

__all__ = [
    "plot_ball_film", "plot_film_profiles", "plot_friction_vs_speed", "plot_oring",
    "plot_oring_cycle",
    "plot_reynolds_cylinder",
    "plot_slider",
    "plot_dt_study", "plot_hertz_pressure", "plot_wear_ball", "plot_wear_pin", "pyplot"]
__all__ += ["plot_groove", "plot_pressure_across"]
