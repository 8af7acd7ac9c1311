"""Registry of runnable cases: ``tribofx run CASE``."""

from .contact_ironing import IroningCase
from .contact_patch import ContactPatchCase
from .contact_two_cylinders import TwoCylindersCase
from .ehl_ball import EHLBallCase
from .ehl_cylinder_layer import EHLCylinderLayerCase
from .ehl_oring import EHLORingCase
from .ehl_squeeze import EHLSqueezeCase
from .ehl_two_cylinders import EHLTwoCylindersCase
from .hertz import HertzCase
from .reynolds_cylinder import CylinderCase
from .reynolds_slider import SliderCase
from .stribeck import StribeckCase
from .wear_ball_flat import WearBallCase
from .wear_ball_halfspace import WearBallHalfspaceCase
from .wear_lubricated import WearLubricatedCase
from .wear_pin import WearPinCase
from .wear_reciprocating import WearReciprocatingCase

__all__ = ["CASES", "get_case"]

CASES = {c.name: c for c in (HertzCase, SliderCase, CylinderCase, EHLCylinderLayerCase,
                                  WearPinCase, WearBallHalfspaceCase, EHLBallCase, WearBallCase,
                                  EHLORingCase, EHLSqueezeCase, EHLTwoCylindersCase,
                                  TwoCylindersCase, ContactPatchCase, IroningCase,
                                  WearReciprocatingCase, StribeckCase,
                                  WearLubricatedCase)}


def get_case(name):
    """Return the case class called ``name`` or raise :class:`tribofx.params.InputError`."""
    from ..params import InputError

    if name not in CASES:
        raise InputError(f"unknown case {name!r}; available: {', '.join(sorted(CASES))}")
    return CASES[name]
