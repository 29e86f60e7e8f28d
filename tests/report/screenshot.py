#!/usr/bin/env python3
"""The README's picture of the HTML report: renders a report and saves the top of its page (the
header, the summary and the first section down to its first plot) as a PNG, 1280 CSS pixels wide,
from headless Chromium.

    tests/report/screenshot.py --report results/baseline.json --out docs/report.png

Needs matplotlib (for bspbench report) and Chromium (apt-get install chromium; .ci/setup has both).
Regenerate the picture when the report's look changes.
"""
import argparse
import os
import sys
import tempfile
import subprocess

import browser

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTH, HEIGHT = 1280, 900
BUDGET_BYTES = 300_000  # the picture is committed; keep the repository light
# The bottom of the first section's first plot, in CSS pixels from the top of the page.
FIRST_PLOT_BOTTOM = """(() => {
    const h2 = document.querySelector('h2');
    const img = h2 && [...document.images].find(i => h2.compareDocumentPosition(i) & Node.DOCUMENT_POSITION_FOLLOWING);
    return img ? img.getBoundingClientRect().bottom + scrollY : null;
})()"""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--report", required=True, help="a report of bspbench sweep")
    parser.add_argument("--out", required=True, help="the PNG to write")
    parser.add_argument("--bspbench", default=os.path.join(HERE, "..", "..", "build", "bspbench"))
    parser.add_argument("--height", type=int, help="CSS pixels from the top (default: to the end of the first plot)")
    args = parser.parse_args()
    if not browser.find_chromium():
        sys.exit("screenshot.py: chromium is not installed (apt-get install chromium)")
    with tempfile.TemporaryDirectory(prefix="bspbench-screenshot-") as tmp:
        # The page prints the command that made it; rendered from tmp as `--in results/NAME --out
        # results/report`, it shows the README's layout rather than a temporary path.
        os.mkdir(os.path.join(tmp, "results"))
        name = os.path.basename(args.report)
        os.symlink(os.path.abspath(args.report), os.path.join(tmp, "results", name))
        subprocess.run([os.path.abspath(args.bspbench), "report", "--in", f"results/{name}", "--out", "results/report"],
                       cwd=tmp, check=True, stdout=subprocess.DEVNULL)
        with browser.Browser(os.path.join(tmp, "chromium.log")) as chromium:
            page = chromium.open("file://" + os.path.join(tmp, "results", "report", "index.html"), WIDTH, HEIGHT)
            height = args.height or page.evaluate(FIRST_PLOT_BOTTOM) or HEIGHT
            clip = page.screenshot(args.out, height=round(height) + 16)
            for line in page.problems():
                print(f"screenshot.py: warning: the page logged {line}", file=sys.stderr)
    size = os.path.getsize(args.out)
    print(f"wrote {args.out}: {clip['width']:.0f} x {clip['height']:.0f} px, {size // 1000} KB")
    if size > BUDGET_BYTES:
        print(f"screenshot.py: warning: over {BUDGET_BYTES // 1000} KB; pass a smaller --height", file=sys.stderr)


if __name__ == "__main__":
    main()
