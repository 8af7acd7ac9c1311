"""Case parameters: declaration, parsing of ``--set key=value`` and validation.

Every violation raises :class:`InputError` with a one-line message; the CLI turns
it into exit status 2.
"""

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .meshes.errors import InputError

__all__ = ["InputError", "Param", "number_list", "resolve"]


@dataclass(frozen=True)
class Param:
    """One case parameter.

    Attributes:
        name: key used with ``--set``.
        type: ``int``, ``float``, ``str`` or ``bool``, or a function of the text
            (e.g. ``hertz``'s ``dim``: 2, 3 or "axisymmetric").
        default: default value (None: derived by the case from the others).
        unit: unit string (``"-"`` for dimensionless).
        doc: one-line description.
        choices: allowed values for strings/ints.
        lower, upper: open bounds (``lower < value < upper``) unless ``closed``.
        closed: bounds are inclusive.
        infinite: +inf is allowed (e.g. a rigid body's modulus, a flat body's radius).
    """

    name: str
    type: Callable[[str], Any]
    default: object
    unit: str
    doc: str
    choices: tuple | None = None
    lower: float | None = None
    upper: float | None = None
    closed: bool = False
    infinite: bool = False

    def parse(self, text):
        """Convert ``text`` to the parameter's type and check its range."""
        try:
            if self.type is bool:
                low = text.strip().lower()
                if low not in ("true", "false", "1", "0", "yes", "no"):
                    raise ValueError
                value = low in ("true", "1", "yes")
            else:
                value = self.type(text)
        except ValueError:
            raise InputError(
                f"parameter {self.name!r} expects {self.type.__name__}, got {text!r}"
            ) from None
        self.check(value)
        return value

    def check(self, value):
        """Raise :class:`InputError` if ``value`` is outside the allowed set or range."""
        if self.choices is not None and value not in self.choices:
            raise InputError(
                f"parameter {self.name!r} must be one of {list(self.choices)}, got {value!r}"
            )
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            if not math.isfinite(value) and not (self.infinite and value == math.inf):
                raise InputError(f"parameter {self.name!r} must be finite, got {value}")
            lo, hi = self.lower, self.upper
            if lo is not None and (value < lo or (value == lo and not self.closed)):
                rel = ">=" if self.closed else ">"
                raise InputError(f"parameter {self.name!r} must be {rel} {lo} {self.unit}, "
                                 f"got {value}")
            if hi is not None and (value > hi or (value == hi and not self.closed)):
                rel = "<=" if self.closed else "<"
                raise InputError(f"parameter {self.name!r} must be {rel} {hi} {self.unit}, "
                                 f"got {value}")


def resolve(params, overrides):
    """Return {name: value} from declared ``params`` and ``overrides`` {name: text}."""
    table = {p.name: p for p in params}
    values = {p.name: p.default for p in params}
    for key, text in overrides.items():
        if key not in table:
            raise InputError(f"unknown parameter {key!r}; known: {', '.join(table)}")
        values[key] = table[key].parse(text)
    return values


def number_list(text, name, kind=float, allow_empty=False):
    """Numbers of a comma- (or semicolon-) separated parameter text, e.g. ``"0.5,1"``.

    Raises :class:`InputError` (one line, naming the parameter) for a malformed
    entry, or for an empty list unless ``allow_empty``.
    """
    try:
        vals = [kind(t) for t in str(text).replace(";", ",").split(",") if t.strip()]
    except ValueError:
        raise InputError(f"parameter {name!r} expects comma-separated numbers, "
                         f"got {text!r}") from None
    if not vals and not allow_empty:
        raise InputError(f"parameter {name!r} is empty")
    if not all(math.isfinite(x) for x in vals):
        raise InputError(f"parameter {name!r} must be finite, got {text!r}")
    return vals

