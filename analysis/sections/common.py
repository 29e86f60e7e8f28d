"""What every section module shares: the Section it returns, the Context it is given, and the helpers
several sections use (names, the report's summaries as cells, the metrics' documentation, plots).

A section module exposes render(report, ctx) -> Section, or None when the report has nothing for
it; sections/__init__.py lists them in page order.
"""
import json
import os
import re
from dataclasses import dataclass, field

from tables import Cell

DPI = 100
MARKERS = "osD^vP*Xh<>p"


@dataclass
class Context:
    """What a section needs besides the report: where the page goes and how to remake it."""
    out_dir: str    # where index.html and the plots go
    command: str    # remakes a table: the sweep, then this page (with its --format)
    how: str        # a paragraph naming the commands that reproduce a section
    baseline: tuple = None  # (path, report, comparison path) with --baseline


@dataclass
class Section:
    toc: list       # (anchor, title) entries of the page's contents
    body: str       # HTML
    tables: list = field(default_factory=list)  # every Table of the body, for --format
    alert: str = ""  # HTML shown under the page's header, above everything else
    lead: bool = False  # the body goes before the contents rather than after them


def slug(text):
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", text)


def kind(agg):
    return agg.get("kind", "draw")


def aggregates_of(report, wanted):
    return [a for a in report["aggregates"] if kind(a) == wanted]


def is_float(entry):
    """Whether an aggregate or a run's id is of the float kernel: a float run names no kernel. The
    exact kernel's runs are the kernel section's, never mixed into the float tables."""
    return entry.get("kernel", "float") == "float"


def value(entry, section, name):
    """The mean over seeds of a by_n entry's metric or timing; None when it has none."""
    v = entry.get(section, {}).get(name)
    return None if v is None else v["mean"]


def plain(x):
    """A number as Python writes it (10000, 0.5, 2.0), not rounded or grouped as tables.number does."""
    return Cell(x, str(x))


def summary_text(summary):
    """Mean ± half the 95% interval over seeds (the mean alone without an interval)."""
    if summary is None:
        return ""
    ci = summary.get("ci95")
    text = f"{summary['mean']:.4g}"
    if ci is not None and ci[1] > ci[0]:
        text += f" ± {(ci[1] - ci[0]) / 2:.2g}"
    return text


def summary_cell(summary):
    return None if summary is None else Cell(summary["mean"], summary_text(summary))


def load_metric_docs():
    path = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "metric_docs.json")
    with open(path, encoding="utf-8") as f:
        return json.load(f)


METRIC_DOCS = load_metric_docs()


def doc_of(key):
    return METRIC_DOCS["metrics"].get(key, {"group": "other", "unit": "", "better": "", "meaning": ""})
