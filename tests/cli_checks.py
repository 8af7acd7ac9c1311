"""Shared check of the CLI's bad-input contract (used by the user-mesh tests)."""


def assert_one_line_error(p, fragment, out):
    """Exit status 2, exactly one line on stderr containing ``fragment``, nothing in ``out``."""
    assert p.returncode == 2, p.stderr
    lines = [ln for ln in p.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, p.stderr
    assert fragment in lines[0] and "Traceback" not in p.stderr, lines[0]
    assert not out.exists()   # nothing written
