#!/usr/bin/python3
"""Render a bspbench sweep report (analysis/SCHEMA.md) as an HTML page with plots.

    /usr/bin/python3 analysis/report.py --in results/report.json --out results/report

(`bspbench report --in FILE --out DIR` runs this.) Writes DIR/index.html and the PNG plots it links.
This file makes the page: the header (suite, summary, environment), the contents and the sections,
and with --format the export of every table into DIR/tables. Each section is a module of
analysis/sections, listed in page order in sections/__init__.py: with --baseline the changes
against it, then who wins where (verdicts), the cost model, the theory check, the glossary, a
section per drawing scene, set operations (merge runs), dynamic scenes (animate runs), occlusion
culling (occlude runs), 2D segments against the Paterson–Yao bound and the Doom maps. Every
statistic a section shows is either report.json's (the aggregates' intervals and growth fits, the
regression gate's tests in comparison.json) or one only the report computes (analysis/stats.py).

Each section names the commands that reproduce it: the sweep of the report's suite, then this page.

Needs matplotlib (Debian: python3-matplotlib; call /usr/bin/python3, a pyenv python3 may lack it).
Exit status: 0 written, 2 bad input (unreadable file, not a bspbench report, other version).
"""
import argparse
import html
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display; before any section imports pyplot

from sections import SECTIONS  # noqa: E402  (this script's own modules, beside it)
from sections.common import Context, plain, slug  # noqa: E402
from tables import EXTENSIONS, Cell, Column, Table  # noqa: E402

SCHEMA = "bspbench-report"
# Version 5 only added doom runs, so a version 4 report reads as one without them.
VERSIONS = (4, 5)


def fail(message):
    print("report.py: " + message, file=sys.stderr)
    sys.exit(2)


def load(path):
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{path}: cannot read a JSON report ({e})")
    if not isinstance(report, dict) or report.get("schema") != SCHEMA:
        fail(f"{path}: not a bspbench report")
    if report.get("version") not in VERSIONS:
        fail(f"{path}: report version {report.get('version')}, this script reads versions "
             + " and ".join(map(str, VERSIONS)))
    return report


ENVIRONMENT_COLUMNS = (("date_utc", "date (UTC)"), ("git_revision", "revision"), ("build_type", "build"),
                       ("compiler", "compiler"), ("flags", "flags"), ("cpu_model", "CPU"),
                       ("hardware_threads", "hardware threads"), ("threads", "threads used"), ("host", "host"))
SUMMARY_ROWS = (("runs", "runs"), ("failures", "failed jobs"), ("invariant_violations", "invariant violations"),
                ("validation_violations", "order violations (Embree)"),
                ("ray_shoot_mismatches", "ray-shooting mismatches"),
                ("others_violations", "violations in nodes made by external builders or shipped with a WAD"),
                ("complete", "every job of the suite ran"))


def environment_table(report):
    """One row per shard: where and how it ran, and the calibration its timings are relative to."""
    rows = []
    for sh in report["shards"]:
        env = sh.get("environment", {})
        seconds = sh.get("calibration", {}).get("seconds", float("nan"))
        rows.append([f"{sh['index']}/{sh['count']}"] + [plain(env.get(key, "—")) for key, _ in ENVIRONMENT_COLUMNS]
                    + [Cell(seconds, f"{seconds:.4g}")])
    return Table("environment", "Environment: where and how each shard ran",
                 [("shard", "")] + [(label, "") for _, label in ENVIRONMENT_COLUMNS] + [("calibration s", "")], rows)


def summary_table(summary):
    return Table("summary", "Summary of the runs", [Column("count", left=True), Column("value")],
                 [[label, plain(summary[key])] for key, label in SUMMARY_ROWS if key in summary], row_heads=True)


def header(report):
    """The page's head and its two tables (summary and environment), which export like any other."""
    suite = report["suite"]
    source = suite.get("source")
    text = ""
    if isinstance(source, dict):
        text = (f"<details><summary>suite file {html.escape(str(source.get('path', '')))} "
                f"({html.escape(str(source.get('hash', '')))})</summary>"
                f"<pre>{html.escape(str(source.get('text', '')))}</pre></details>")
    summary, environment = summary_table(report.get("summary", {})), environment_table(report)
    return (f"<h1>bspbench report: suite {html.escape(suite['name'])}</h1>"
            f"<p>definition {html.escape(suite['definition_hash'])}, {suite['jobs']} jobs</p>{text}"
            f"{summary.html()}<h3>Environment</h3>{environment.html()}"
            "<p>Intervals are 95% Student-t intervals over seeds (± half-width). The scene sections' growth "
            "exponents k fit y = c·n^k by least squares on log-log axes over every run; the theory check fits "
            "the sizes' geometric means over seeds and gives each exponent its interval.</p>"), [summary, environment]


STYLE = ("<style>body{font-family:sans-serif;margin:1em 2em}table{border-collapse:collapse;font-size:12px}"
         "td,th{border:1px solid #ccc;padding:2px 6px;text-align:right}th{background:#eee}"
         ".scroll{overflow-x:auto}img{max-width:100%}.alert{border:2px solid #c00;background:#fee;padding:4px 12px}"
         ".ok{border:1px solid #393;background:#efe;padding:4px 12px}"
         ".notice{border:1px solid #b80;background:#fff8e0;padding:4px 12px}.note{font-size:12px;color:#444}"
         ".cmd{font-size:12px}</style>")


def sweep_command(report, source):
    suite, shards = report["suite"]["name"], len(report["shards"])
    source_file = report["suite"].get("source")
    if isinstance(source_file, dict) and source_file.get("path"):
        suite = source_file["path"]  # a user's suite file; its text is in the report (suite.source)
    if shards > 1:
        return (f"bspbench sweep --suite {suite} --shard I/{shards} --out shard-I.json (I = 0 to {shards - 1}); "
                f"bspbench merge-reports --out {source} shard-*.json")
    return f"bspbench sweep --suite {suite} --out {source}"


def command_text(report, source, out_dir, extra=""):
    """The commands that remake a table or plot: the sweep, then this page."""
    return f"{sweep_command(report, source)}; bspbench report --in {source} --out {out_dir}{extra}"


def reproduce(report, source, out_dir):
    """The commands that remake a section's tables and plots: the sweep (as shards merged, when it
    ran so) and this page."""
    return (f"<p class=cmd>Reproduce: <code>{html.escape(sweep_command(report, source))}</code>, then "
            f"<code>{html.escape(f'bspbench report --in {source} --out {out_dir}')}</code></p>")


def write_exports(tables, out_dir, fmt):
    folder = os.path.join(out_dir, "tables")
    os.makedirs(folder, exist_ok=True)
    for t in tables:
        path = os.path.join(folder, f"{slug(t.name)}.{EXTENSIONS[fmt]}")
        with open(path + ".tmp", "w", encoding="utf-8") as f:
            f.write(t.render(fmt))
        os.replace(path + ".tmp", path)


def page(head, sections):
    """The page: header, the sections' alerts, the leading sections, the contents, the other sections."""
    alerts = "".join(s.alert for s in sections)
    lead = "".join(s.body for s in sections if s.lead)
    toc = "".join(f"<li><a href='#{anchor}'>{html.escape(title)}</a></li>" for s in sections for anchor, title in s.toc)
    body = "".join(s.body for s in sections if not s.lead)
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>bspbench report</title>{STYLE}</head>"
            f"<body>{head}{alerts}{lead}<h2>Contents</h2><ul>{toc}</ul>{body}</body></html>\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--in", dest="input", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--baseline", help="an earlier report of the same suite")
    parser.add_argument("--comparison", help="the regression gate's comparison of --baseline and --in (JSON)")
    parser.add_argument("--format", choices=sorted(EXTENSIONS), help="also export the tables into OUT/tables")
    args = parser.parse_args()
    report = load(args.input)
    baseline = load(args.baseline) if args.baseline else None
    if baseline is not None and not args.comparison:
        fail("--baseline needs --comparison (bspbench report --baseline writes it)")
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        fail(f"{args.out}: cannot create the output directory ({e})")
    extra = f" --format {args.format}" if args.format else ""
    ctx = Context(args.out, command_text(report, args.input, args.out, extra),
                  reproduce(report, args.input, args.out),
                  None if baseline is None else (args.baseline, baseline, args.comparison))
    head, head_tables = header(report)
    sections = [s for s in (render(report, ctx) for render in SECTIONS) if s is not None]
    if args.format:
        write_exports(head_tables + [t for s in sections for t in s.tables], args.out, args.format)
    tmp = os.path.join(args.out, "index.html.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page(head, sections))
    os.replace(tmp, os.path.join(args.out, "index.html"))


if __name__ == "__main__":
    main()
