#!/usr/bin/env python3
"""bspbench report answers its questions on a real report, compares two reports and exports tables.

    check_sections.py --bspbench build/bspbench --report results/baseline.json --work DIR

The "new" report is the baseline with one heuristic's default parameter changed, as a change to its
code would change it: crystal's candidates 20 -> 8, its job keys and its fragments up by 7 in every
run (the runs pair by command, as the same jobs of two builds do). The page
must list exactly crystal's groups as changed, name the parameter, keep every timing group "within"
(the samples are the same), and still carry the verdict, cost-model, theory and glossary sections,
without a raw JSON dump; --format latex must write the tables; a bad --format must exit 2.
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys

CHANGED = "crystal"


def fail(message):
    print("check_sections: FAIL: " + message, file=sys.stderr)
    sys.exit(1)


def plant(baseline_path, new_path):
    with open(baseline_path, encoding="utf-8") as f:
        report = json.load(f)
    changed = 0
    for run in report["runs"]:
        rid = run["id"]
        if rid.get("kind", "draw") == "draw" and rid["heuristic"] == CHANGED:
            rid["heuristic_params"]["candidates"] = 8
            run["metrics"]["fragments"] += 7
            run["key"] = "c0ffee" + run["key"][6:]  # a job key covers the resolved parameters
            changed += 1
    with open(new_path, "w", encoding="utf-8") as f:
        json.dump(report, f)
    return changed


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--bspbench", required=True)
    parser.add_argument("--report", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    new = os.path.join(args.work, "new.json")
    if plant(args.report, new) == 0:
        fail(f"{args.report} has no {CHANGED} drawing runs to change")
    out = os.path.join(args.work, "html")
    run = subprocess.run([args.bspbench, "report", "--in", new, "--baseline", args.report, "--out", out,
                          "--format", "latex"], capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"report exited {run.returncode}: {run.stderr.strip()}")
    with open(os.path.join(out, "index.html"), encoding="utf-8") as f:
        page = f.read()
    for anchor in ("changes", "verdicts", "costmodel", "theory", "glossary"):
        if f"id='{anchor}'" not in page:
            fail(f"the page has no section '{anchor}'")
    if '{"' in page:
        fail("the page holds a raw JSON dump")
    table = re.search(r"<table id='table-changes-deterministic'>(.*?)</table>", page, re.S)
    if not table:
        fail("no table of deterministic changes")
    rows = re.findall(r"<tr>(.*?)</tr>", table.group(1), re.S)[1:]
    labels = {re.findall(r"<td>(.*?)</td>", r)[1].split(" (")[0] for r in rows}  # any shape
    if not rows or labels != {CHANGED}:
        fail(f"changed groups should be exactly {CHANGED}'s, the page lists {sorted(labels)}")
    if "candidates: 20 → 8" not in table.group(1):
        fail("the changed parameter is not named")
    if not all("fragments" in r for r in rows):
        fail("a changed group lists a metric other than fragments")
    timings = re.search(r"<table id='table-changes-timings'>(.*?)</table>", page, re.S)
    verdicts = re.findall(r"<td>(?:<b>)?(slower|faster|within)(?:</b>)?</td>", timings.group(1)) if timings else []
    if not verdicts or set(verdicts) != {"within"}:
        fail(f"identical timings should all be 'within', the page says {sorted(set(verdicts))}")
    if not os.path.exists(os.path.join(out, "comparison.json")):
        fail("comparison.json is missing")
    exported = glob.glob(os.path.join(out, "tables", "*.tex"))
    verdict_tables = [p for p in exported if os.path.basename(p).startswith("verdicts-")]
    if not verdict_tables or not any(os.path.basename(p).startswith("metrics-") for p in exported):
        fail(f"--format latex wrote {len(exported)} tables, without the verdict or metric tables")
    with open(verdict_tables[0], encoding="utf-8") as f:
        if not f.read().startswith("\\begin{table}"):
            fail(f"{verdict_tables[0]} is not a LaTeX table")
    bad = subprocess.run([args.bspbench, "report", "--in", new, "--out", out, "--format", "docx"],
                         capture_output=True, text=True)
    if bad.returncode != 2:
        fail(f"--format docx exited {bad.returncode}, not 2")
    print(f"check_sections: {len(rows)} changed rows of {CHANGED}, {len(verdicts)} timing groups within, "
          f"{len(exported)} LaTeX tables")


if __name__ == "__main__":
    main()
