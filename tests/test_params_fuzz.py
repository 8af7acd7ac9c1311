"""Every parameter of every case, given a bad value, stops at validation with InputError
(the CLI's one line and exit status 2, tests/test_cli.py) or is a valid input — never
another exception (a crash, or a traceback in place of the one-line message)."""

import pytest

from tribofx.cases import CASES
from tribofx.params import InputError, declared, resolve

BAD = ("0", "-1", "nan", "inf", "-inf", "1e300", "abc", "1.5")


@pytest.mark.parametrize("name", sorted(CASES))
def test_every_parameter_fails_cleanly_or_is_valid(name):
    case = CASES[name]
    crashes = []
    for p in declared(case.Params):
        for text in BAD:
            try:
                v = resolve(case.Params, {p.name: text})
                case.validate(v)
                if hasattr(case, "resolved"):
                    case.resolved(v)
            except InputError:
                pass
            except Exception as err:  # noqa: BLE001 - any other exception is the failure
                crashes.append(f"{p.name}={text}: {type(err).__name__}: {err}")
    assert not crashes, crashes
