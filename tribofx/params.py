"""Case parameters: a typed dataclass per case, parsing of ``--set key=value``, validation.

A case declares its parameters as a frozen dataclass derived from
:class:`CaseParams`, one field per parameter, each made by :func:`param` (default,
unit, one-line help, bounds or choices as the field's metadata)::

    @dataclass(frozen=True)
    class Params(CaseParams):
        W: float = param(40.0, "N", "normal load", lower=0.0)
        mesh: int = param(1, "-", "refinement level", lower=0, upper=4, closed=True)

:func:`declared` turns the fields into :class:`Param` descriptors (what ``tribofx
list``, the documentation tables and ``--set`` parsing use); :func:`resolve` makes
the parameters from ``--set`` texts; constructing a ``Params`` checks every field
against its bounds.  Every violation raises :class:`InputError` with a one-line
message; the CLI turns it into exit status 2.
"""

from __future__ import annotations

import dataclasses
import math
import types
import typing
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Self, overload

from .meshes.errors import InputError

__all__ = ["CaseParams", "InputError", "Param", "declared", "number_list", "param", "resolve"]


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

    def parse(self, text: str) -> Any:
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

    def check(self, value: object) -> None:
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


def param(default: Any, unit: str, doc: str, *, choices: tuple | None = None,
          lower: float | None = None, upper: float | None = None, closed: bool = False,
          infinite: bool = False, parse: Callable[[str], Any] | None = None) -> Any:
    """Return a parameter field of a case's ``Params`` dataclass (arguments as :class:`Param`).

    ``default`` None: the case derives the value from the others.  ``parse``: a
    function of the ``--set`` text when the field's type is not ``int``, ``float``,
    ``str`` or ``bool`` (e.g. ``hertz``'s ``dim``: 2, 3 or "axisymmetric").
    """
    meta = {"unit": unit, "doc": doc, "choices": choices, "lower": lower, "upper": upper,
            "closed": closed, "infinite": infinite, "parse": parse}
    return dataclasses.field(default=default, metadata={"param": meta})


def _field_type(annotation: Any) -> Callable[[str], Any]:
    """``float`` of ``float`` and of ``float | None``."""
    if isinstance(annotation, types.UnionType):
        args = [a for a in typing.get_args(annotation) if a is not type(None)]
        if len(args) == 1:
            return args[0]
    if annotation in (int, float, str, bool):
        return annotation
    raise TypeError(f"a parameter field of type {annotation!r} needs parse=")


def declared(cls: type) -> tuple[Param, ...]:
    """Return the :class:`Param` descriptors of the ``Params`` dataclass ``cls``.

    In the order a reader meets them: the class's own fields first, then those of
    each base (e.g. :class:`tribofx.cases.film_setup.FluidParams`).
    """
    hints = typing.get_type_hints(cls)
    fields = {f.name: f for f in dataclasses.fields(cls)}
    order: list[str] = []
    for klass in cls.__mro__:
        for key in vars(klass).get("__annotations__", {}):
            if key in fields and key not in order:
                order.append(key)
    out = []
    for key in order:
        f = fields[key]
        meta = dict(f.metadata["param"])
        parse = meta.pop("parse") or _field_type(hints[key])
        out.append(Param(key, parse, f.default, **meta))
    return tuple(out)


@dataclass(frozen=True)
class CaseParams:
    """Base of a case's parameter dataclass: every field is checked when it is made."""

    def __post_init__(self) -> None:
        for p in declared(type(self)):
            value = getattr(self, p.name)
            if value is not None or p.default is not None:
                p.check(value)

    def as_dict(self) -> dict[str, Any]:
        """Return {name: value} of every parameter, in declaration order."""
        return {p.name: getattr(self, p.name) for p in declared(type(self))}

    def replace(self, **changes: Any) -> Self:
        """Return a copy with ``changes`` (checked as the original was)."""
        return dataclasses.replace(self, **changes)


def resolve[P: CaseParams](cls: type[P], overrides: Mapping[str, Any]) -> P:
    """Return the parameters ``cls`` with ``overrides`` {name: text} parsed over the defaults."""
    table = {p.name: p for p in declared(cls)}
    values = {}
    for key, text in overrides.items():
        if key not in table:
            raise InputError(f"unknown parameter {key!r}; known: {', '.join(table)}")
        values[key] = table[key].parse(str(text))
    return cls(**values)


@overload
def number_list(text: str, name: str, kind: type[int],
                allow_empty: bool = False) -> list[int]: ...


@overload
def number_list(text: str, name: str, kind: Callable[[str], float] = float,
                allow_empty: bool = False) -> list[float]: ...


def number_list(text: str, name: str, kind: Callable[[str], float] = float,
                allow_empty: bool = False) -> list[int] | list[float]:
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

