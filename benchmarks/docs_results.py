"""Write the generated parts of ``docs/cases/<case>.md`` from the cases themselves.

Each case page has two generated blocks, and its figures' stamps:

* ``<!-- params:begin -->`` … ``<!-- params:end -->``: the case's parameters (name,
  default, unit, description) from its declaration, as ``tribofx list`` prints them;
* ``<!-- results:begin -->`` … ``<!-- results:end -->``: the scalar results of the
  page's command (the first ``tribofx run`` line of its "Run it" block), run into
  ``results/docs/<case>/`` and read back from that run's ``summary.json``, stamped
  with the commit, the machine, the number of ranks and the wall time;
* after each figure's caption, ``<!-- figure -->`` and the commit and date the
  figure file was last committed at (from git): a study's figure keeps the
  numbers of the run that drew it, and the stamp says which code that was.

So the numbers on a page are those of a run of the code as committed, never typed
in.  Usage::

    python benchmarks/docs_results.py                  # every case: parameters and results
    python benchmarks/docs_results.py --params-only    # the parameter tables alone (fast)
    python benchmarks/docs_results.py --cases hertz,wear-pin
"""

import argparse
import json
import os
import platform
import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGES = ROOT / "docs" / "cases"
BLOCK = "<!-- {0}:begin -->\n{1}<!-- {0}:end -->"


def replace_block(text, name, body):
    """Return ``text`` with the generated block ``name`` holding ``body``."""
    pattern = re.compile(rf"<!-- {name}:begin -->\n.*?<!-- {name}:end -->", re.S)
    if not pattern.search(text):
        raise SystemExit(f"no {name} block in the page")
    return pattern.sub(lambda _: BLOCK.format(name, body), text)


FIGURE = re.compile(r"!\[[^\]]*\]\(\.\./figures/([^)]+)\)")
STAMP = re.compile(r" *<!-- figure -->.*$")


def figure_stamp(name):
    """'figure: commit `abc1234`, 2026-12-01' of the last commit of ``docs/figures/name``."""
    out = subprocess.run(["git", "log", "-1", "--format=%h %cs", "--", f"docs/figures/{name}"],
                         cwd=ROOT, capture_output=True, text=True).stdout.split()
    return f"<!-- figure --> *(figure: commit `{out[0]}`, {out[1]})*" if out else ""


def stamp_figures(text):
    """Return ``text`` with each figure's caption (the paragraph after it) stamped."""
    lines = text.split("\n")
    for i, line in enumerate(lines):
        m = FIGURE.match(line.strip())
        if not m:
            continue
        j = i + 1
        while j < len(lines) and not lines[j].strip():
            j += 1
        if j < len(lines) and lines[j].startswith("**"):      # the caption paragraph
            while j + 1 < len(lines) and lines[j + 1].strip():
                j += 1
            stamp = figure_stamp(m.group(1))
            if stamp:
                lines[j] = STAMP.sub("", lines[j]) + " " + stamp
    return "\n".join(lines)


def params_table(case):
    """Markdown table of a case's parameters (those every case takes are in the README)."""
    from tribofx.params import declared

    rows = ["| parameter | default | unit | meaning |", "|---|---|---|---|"]
    for p in declared(case.Params):
        doc = str(p.doc).replace("|", "\\|")
        if p.choices:
            doc += " (" + ", ".join(str(c) for c in p.choices) + ")"
        unit = str(p.unit).replace("|", "\\|")
        rows.append(f"| `{p.name}` | `{p.default!r}` | {unit} | {doc} |")
    return "\n".join(rows) + "\n"


def page_command(text):
    """The ``tribofx run`` command of a page's "Run it" block, as arguments."""
    m = re.search(r"^\.venv/bin/tribofx (run [^\n]*?)( --out \S+)?$", text, re.M)
    if m is None:
        raise SystemExit("no '.venv/bin/tribofx run ...' line in the page")
    return shlex.split(m.group(1))


def machine():
    """CPU model and core count of this machine."""
    model = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores"


def commit():
    """The commit the code runs at (``-dirty`` with uncommitted changes outside ``docs/``)."""
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                          capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--",
                            ".", ":!docs"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    return head + ("-dirty" if dirty else "")


def fmt(value):
    """A scalar for a table cell."""
    if isinstance(value, float):
        return f"{value:.6g}"
    return f"`{value}`" if isinstance(value, str) else str(value)


def results_table(summary, args, stamp):
    """Markdown of a run's scalar results (lists and maps are in its summary.json)."""
    rows = [f"`tribofx {' '.join(args)}` — status `{summary['status']}`, {stamp}, "
            f"{summary.get('mpi_size', 1)} rank(s), {summary.get('wall_time_s', 0):.1f} s, "
            f"{summary.get('num_dofs', '?')} unknowns.", "",
            "| result | value | unit |", "|---|---|---|"]
    for key, entry in summary["results"].items():
        value = entry["value"]
        if isinstance(value, (list, dict)) or "wall" in key:
            continue
        rows.append(f"| `{key}` | {fmt(value)} | {entry.get('unit', '-')} |")
    return "\n".join(rows) + "\n"


def main(argv=None):
    """Regenerate the blocks of the chosen case pages."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default="", help="comma-separated cases (default: all)")
    parser.add_argument("--params-only", action="store_true", help="do not run the cases")
    parser.add_argument("--out", default=str(ROOT / "results" / "docs"))
    a = parser.parse_args(argv)
    import dolfinx_solver  # noqa: F401  (before dolfinx / petsc4py)

    from tribofx.cases import CASES

    names = [c for c in a.cases.split(",") if c] or sorted(CASES)
    stamp = f"commit `{commit()}`, {machine()}"
    for name in names:
        page = PAGES / f"{name}.md"
        text = replace_block(page.read_text(), "params", params_table(CASES[name]))
        text = stamp_figures(text)
        if not a.params_only:
            args = page_command(text)
            out = Path(a.out) / name
            env = dict(os.environ, UCX_TLS=os.environ.get("UCX_TLS", "self,sm,tcp"))
            cmd = [sys.executable, "-m", "tribofx.cli", *args, "--quiet", "--out", str(out)]
            print(" ".join(cmd), flush=True)
            subprocess.run(cmd, env=env, check=False)
            summary = json.loads((out / "summary.json").read_text())
            text = replace_block(text, "results", results_table(summary, args, stamp))
        page.write_text(text)


if __name__ == "__main__":
    main()
