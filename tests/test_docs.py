"""The documentation stays true to the code: pages, links, figures, parameters, results.

* every case has a page ``docs/cases/<case>.md``, and every page a case;
* every relative link and figure of ``README.md`` and ``docs/`` exists;
* the README stays short (at most 150 lines, no table cell over 300 characters);
* each case page's parameter table lists exactly the case's parameters with their
  defaults and units (``make docs-results`` writes it from the declaration);
* each case page's results were written by ``benchmarks/docs_results.py`` from a
  run of the page's own command, stamped with a commit.
"""

import re
from pathlib import Path

import pytest

from tribofx.cases import CASES
from tribofx.params import declared

ROOT = Path(__file__).resolve().parents[1]
PAGES = ROOT / "docs" / "cases"
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def _block(text, name):
    m = re.search(rf"<!-- {name}:begin -->\n(.*?)<!-- {name}:end -->", text, re.S)
    assert m is not None, f"no {name} block"
    return m.group(1)


def test_every_case_has_a_page_and_every_page_a_case():
    pages = {p.stem for p in PAGES.glob("*.md")}
    assert pages == set(CASES)


@pytest.mark.parametrize("doc", [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))],
                         ids=lambda p: str(p.relative_to(ROOT)))
def test_links_and_figures_exist(doc):
    for target in LINK.findall(doc.read_text()):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue                                    # a URL or an anchor of the page
        path = (doc.parent / target.split("#")[0]).resolve()
        assert path.exists(), f"{doc.name} links {target}, which does not exist"


def test_readme_is_short():
    lines = (ROOT / "README.md").read_text().splitlines()
    assert len(lines) <= 150
    cells = [c for line in lines if line.startswith("|") for c in line.split("|")]
    assert max(map(len, cells)) <= 300


@pytest.mark.parametrize("name", sorted(CASES))
def test_case_page_parameters_are_the_declaration(name):
    table = _block((PAGES / f"{name}.md").read_text(), "params")
    rows = re.findall(r"^\| `([^`]+)` \| `([^`]*)` \| ((?:\\\||[^|])*) \|", table, re.M)
    expected = [(p.name, repr(p.default), p.unit.replace("|", "\\|"))
                for p in declared(CASES[name].Params)]
    assert [(n, d, u.strip()) for n, d, u in rows] == expected


@pytest.mark.parametrize("name", sorted(CASES))
def test_case_page_results_are_of_its_command(name):
    text = (PAGES / f"{name}.md").read_text()
    command = re.search(r"^\.venv/bin/tribofx (run [^\n]*?) --out \S+$", text, re.M).group(1)
    results = _block(text, "results")
    stamp = re.match(r"`tribofx (run [^`]*)` — status `([^`]*)`, commit `([0-9a-f]+)", results)
    assert stamp is not None, "results not generated (make docs-results)"
    assert stamp.group(1) == command
    assert stamp.group(2) == "ok"
