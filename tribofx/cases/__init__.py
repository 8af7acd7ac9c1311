"""Registry of runnable cases: ``tribofx run CASE``."""

from .contact_patch import ContactPatchCase
from .ehl import EHLCylinderLayerCase
from .ehl_ball import EHLBallCase
from .ehl_oring import EHLORingCase
from .ehl_squeeze import EHLSqueezeCase
from .ehl_two_cylinders import EHLTwoCylindersCase
from .hertz import HertzCase
from .ironing import IroningCase
from .reynolds import SliderCase
from .reynolds_cylinder import CylinderCase
from .stribeck import StribeckCase
from .two_cylinders import TwoCylindersCase
from .wear import WearPinCase
from .wear_ball import WearBallCase
from .wear_groove import WearBallHalfspaceCase
from .wear_lubricated import WearLubricatedCase
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
