#!/usr/bin/env python3
"""CTest checks of the HTML report (bspbench report) in headless Chromium; exit 77 (skipped) when
matplotlib or Chromium is missing, except in CI (CI=true), where .ci/setup installs both and a
missing one fails.

  check_report.py render --bspbench EXE --report REPORT.json --out DIR
        renders REPORT.json into DIR (emptied first, so a stale page cannot pass)
  check_report.py check --page DIR --out OUT
        opens DIR/index.html and fails unless every <img> loaded, the page logged no error or
        warning (a failed load counts as an error), and it has a table and an image; saves a
        full-page screenshot, OUT/report-page.png, either way
  check_report.py catches-faults --page DIR --out OUT
        the check itself can fail: a copy of the page with one image link broken and a
        console.error injected (OUT/faulty) must be rejected for both

The page is opened as a file:// URL, the way a reader opens it from disk.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import browser

SKIP = 77
WIDTH, HEIGHT = 1280, 900
# Under the ctest TIMEOUT, so that a hung browser still gets closed by us rather than killed.
DEADLINE_SECONDS = 120
BROKEN_IMAGE = "missing-plot.png"
INJECTED = "injected by check_report.py catches-faults"


def skip(reason):
    if os.environ.get("CI") == "true":  # .ci/setup installs everything: a skip there hides a broken setup
        print(f"FAIL: {reason} (CI must run this test)")
        sys.exit(1)
    print(f"SKIPPED: {reason}")
    sys.exit(SKIP)


def render(args):
    shutil.rmtree(args.out, ignore_errors=True)  # also when skipping: the browser tests then skip too
    python = os.environ.get("BSPBENCH_PYTHON", "/usr/bin/python3")
    if subprocess.run([python, "-c", "import matplotlib"], capture_output=True).returncode != 0:
        skip(f"{python} has no matplotlib (apt-get install python3-matplotlib)")
    start = time.monotonic()
    proc = subprocess.run([args.bspbench, "report", "--in", args.report, "--out", args.out])
    print(f"render: {time.monotonic() - start:.1f} s, exit {proc.returncode}")
    return proc.returncode


def inspect(page_dir, out_dir, screenshot):
    """The page's failures, one line each (none: it passes); saves a full-page screenshot unless
    screenshot is None."""
    index = os.path.join(page_dir, "index.html")
    if not os.path.exists(index):
        return [f"{index} does not exist"]
    os.makedirs(out_dir, exist_ok=True)
    failures = []
    start = time.monotonic()
    with browser.Browser(os.path.join(out_dir, "chromium.log")) as chromium:
        page = chromium.open("file://" + os.path.abspath(index), WIDTH, HEIGHT)
        facts = page.evaluate("""({
            images: Array.from(document.images, i => ({src: i.getAttribute('src'),
                                                         loaded: i.complete && i.naturalWidth > 0})),
            tables: document.querySelectorAll('table').length})""")
        failures += [f"logged: {line}" for line in page.problems()]
        if screenshot:
            clip = page.screenshot(screenshot)
            print(f"screenshot: {screenshot} ({clip['width']:.0f} x {clip['height']:.0f} CSS px)")
    failures += [f"image not loaded: {img['src']}" for img in facts["images"] if not img["loaded"]]
    if not facts["images"]:
        failures.append("the page has no image")
    if not facts["tables"]:
        failures.append("the page has no table")
    if chromium.leftover:
        failures.append(f"Chromium processes left running: {chromium.leftover}")
    print(f"browser: {time.monotonic() - start:.1f} s; {len(facts['images'])} images, {facts['tables']} tables")
    return failures


def check(args):
    failures = inspect(args.page, args.out, os.path.join(args.out, "report-page.png"))
    for line in failures:
        print(f"FAIL: {line}")
    if not failures:
        print("ok: every image loaded, nothing logged")
    return 1 if failures else 0


def catches_faults(args):
    faulty = os.path.join(args.out, "faulty")
    shutil.rmtree(faulty, ignore_errors=True)
    shutil.copytree(args.page, faulty)
    index = os.path.join(faulty, "index.html")
    with open(index, encoding="utf-8") as f:
        text = f.read()
    text, broken = re.subn(r"""(<img\b[^>]*?\bsrc=)(['"])[^'"]*\2""", rf"\1'{BROKEN_IMAGE}'", text, count=1)
    if not broken:
        print(f"FAIL: {args.page}/index.html has no <img src=...> to break")
        return 1
    script = f"<script>console.error('{INJECTED}')</script>"
    text = text.replace("</body>", script + "</body>") if "</body>" in text else text + script
    with open(index, "w", encoding="utf-8") as f:
        f.write(text)
    failures = inspect(faulty, args.out, None)  # the screenshot is the slow part and proves nothing here
    print("the check's verdict on the faulty copy:")
    for line in failures:
        print(f"  {line}")
    wanted = {"the broken image": lambda line: line == f"image not loaded: {BROKEN_IMAGE}",
              "its failed load": lambda line: line.startswith("logged: error") and BROKEN_IMAGE in line,
              "the console.error": lambda line: line == f"logged: console.error: {INJECTED}"}
    missed = [name for name, found in wanted.items() if not any(found(line) for line in failures)]
    for name in missed:
        print(f"FAIL: the check did not report {name}")
    if not missed:
        print("ok: the check reports the broken image, its failed load and the console.error")
    return 1 if missed else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="mode", required=True)
    r = sub.add_parser("render")
    r.add_argument("--bspbench", required=True)
    r.add_argument("--report", required=True)
    r.add_argument("--out", required=True)
    for mode in ("check", "catches-faults"):
        m = sub.add_parser(mode)
        m.add_argument("--page", required=True, help="the directory holding index.html")
        m.add_argument("--out", required=True, help="where the screenshot, the faulty copy and Chromium's log go")
    args = parser.parse_args()
    if args.mode == "render":
        return render(args)
    if not browser.find_chromium():
        skip("chromium is not installed (apt-get install chromium)")
    if not os.path.exists(os.path.join(args.page, "index.html")):
        skip(f"no page in {args.page}: its render test skipped or did not run")

    def out_of_time(_signum, _frame):
        raise TimeoutError(f"not done in {DEADLINE_SECONDS} s")

    signal.signal(signal.SIGALRM, out_of_time)
    signal.alarm(DEADLINE_SECONDS)
    start = time.monotonic()
    status = check(args) if args.mode == "check" else catches_faults(args)
    print(f"{args.mode}: {time.monotonic() - start:.1f} s")
    return status


if __name__ == "__main__":
    sys.exit(main())
