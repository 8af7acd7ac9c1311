"""Interfaces on a body's boundary: contact, lubricating film, wear.

Each interface owns its unknowns on a facet submesh, its residual contributions
(built only by :mod:`tribofx.forms`), the data it refreshes before each assembly
and its outputs; it follows the component protocol of :mod:`tribofx.problem`.
"""

from .contact import Contact
from .film import Film
from .film_options import JFO, FilmScales, Fluid, Penalty, Quadrature
from .prescribed_pressure import PrescribedPressure
from .reynolds_film import ReynoldsFilm
from .rigid_film import RigidFilm
from .two_body_contact import TwoBodyContact
from .two_body_film import TwoBodyFilm
from .wear import Wear

__all__ = ["JFO", "Contact", "Film", "FilmScales", "Fluid", "Penalty", "PrescribedPressure",
           "Quadrature", "ReynoldsFilm", "RigidFilm", "TwoBodyContact", "TwoBodyFilm", "Wear"]
