#!/usr/bin/python3
"""Draw a bspbench history (results over time) as an HTML page with plots.

    /usr/bin/python3 analysis/history.py --data DIR/history.json --out DIR

(`bspbench history --db FILE.sqlite --out DIR` writes history.json from the database and runs
this.) Per suite: the entries, oldest first, with the regression gate's decision on each (judged
against the last k entries of its suite and machine); then, per scene, a plot per timing group
(scene x heuristic x shape, as the gate groups runs): its gated build time, each run's samples over
their in-run reference, a line per machine, each as a ratio to that machine's first entry (solid),
and every metric of the group that ever changed, as a ratio to its first value (dashed). An entry
where the gate found the group slower is marked with a red triangle, an entry the gate failed is
shaded, and a dotted rule marks each change of machine: timings of two machines are not compared. The
tables under each suite list the metrics that changed. Layout of history.json: docs/history.md.

Needs matplotlib (Debian: python3-matplotlib). Exit status: 0 written, 2 bad input.
"""
import argparse
import html
import json
import math
import os
import sys
import time

import matplotlib

matplotlib.use("Agg")  # files only, no display; before pyplot
import matplotlib.pyplot as plt  # noqa: E402

DPI = 100
# Groups per figure (one figure per scene, split when a scene has more).
PER_FIGURE = 12
COLUMNS = 4


def fail(message):
    print(f"history.py: {message}", file=sys.stderr)
    sys.exit(2)


def scene_of(label):
    return label.split(" ", 1)[0]


def series(points, entries):
    """Values by entry index, None where the group has none."""
    values = [None] * len(entries)
    for p in points:
        values[p["i"]] = p["v"]
    return values


def by_machine(entries):
    """machine -> the indices of its entries, in order."""
    out = {}
    for i, e in enumerate(entries):
        out.setdefault(e["machine"], []).append(i)
    return out


def ratio_to_first(values, entries):
    """Each value over the first of its own machine's: times of two machines are never compared,
    not even through a common first point."""
    out = [None] * len(values)
    for indices in by_machine(entries).values():
        first = next((values[i] for i in indices if values[i]), None)
        for i in indices:
            out[i] = values[i] / first if (values[i] is not None and first) else None
    return out


def breaks(entries):
    """Indices i where entry i runs on another machine than entry i - 1."""
    return [i for i in range(1, len(entries)) if entries[i]["machine"] != entries[i - 1]["machine"]]


def per_machine(values, entries):
    """(machine number, xs, ys): a machine's points of the series, so no line joins two machines."""
    for k, indices in enumerate(by_machine(entries).values()):
        xs = [i for i in indices if values[i] is not None]
        if xs:
            yield k, xs, [values[i] for i in xs]


def changed_metrics(group, entries):
    out = {}
    for name, points in group["metrics"].items():
        vals = [v for v in series(points, entries) if v is not None]
        if vals and any(not math.isclose(v, vals[0], rel_tol=1e-9, abs_tol=1e-12) for v in vals):
            out[name] = series(points, entries)
    return out


def draw_scene(labels, groups, entries, path):
    rows = math.ceil(len(labels) / COLUMNS)
    fig, axes = plt.subplots(rows, min(COLUMNS, len(labels)), figsize=(4.2 * min(COLUMNS, len(labels)), 2.9 * rows),
                             squeeze=False)
    cuts = breaks(entries)
    ticks = [e["revision"][:9] for e in entries]
    for ax, label in zip(axes.flat, labels):
        g = groups[label]
        timing = ratio_to_first(series(g["timing"], entries), entries)
        machines = len(by_machine(entries))
        for m, xs, ys in per_machine(timing, entries):
            ax.plot(xs, ys, "-o", color=plt.cm.Blues(1 - 0.5 * m / machines), markersize=3, linewidth=1.2,
                    label="build time" + (f" (machine {m + 1})" if machines > 1 else ""))
        # Metrics are deterministic: the same on every machine, so one line over all entries.
        for k, (name, values) in enumerate(sorted(changed_metrics(g, entries).items())):
            xs = [i for i, v in enumerate(values) if v is not None]
            first = values[xs[0]]
            ax.plot(xs, [values[i] / first if first else None for i in xs], "--", linewidth=1,
                    color=plt.cm.tab10((k + 1) % 10), label=name)
        for i, e in enumerate(entries):
            gate = e["gate"]
            if gate.get("judged") and gate.get("failed"):
                ax.axvspan(i - 0.4, i + 0.4, color="red", alpha=0.08)
            if gate.get("judged") and label in gate.get("slower", []) and timing[i] is not None:
                ax.plot([i], [timing[i]], "v", color="red", markersize=8)
        for c in cuts:
            ax.axvline(c - 0.5, color="gray", linestyle=":", linewidth=1)
        ax.set_title(label, fontsize=8)
        ax.set_xticks(range(len(entries)))
        ax.set_xticklabels(ticks, rotation=60, ha="right", fontsize=6)
        ax.tick_params(axis="y", labelsize=6)
        ax.set_ylabel("ratio to first", fontsize=6)
        handles, names = ax.get_legend_handles_labels()
        unique = dict(zip(names, handles))
        ax.legend(unique.values(), unique.keys(), fontsize=5, loc="best")
    for ax in list(axes.flat)[len(labels):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=DPI)
    plt.close(fig)


def entries_table(suite):
    rows = []
    for n, e in enumerate(suite["entries"]):
        m = suite["machines"][e["machine"]]
        gate = e["gate"]
        if not gate.get("judged"):
            verdict = "not judged (no earlier entry on this machine)"
        elif gate["failed"]:
            verdict = (f"<b>FAILED</b>: {gate['regressions']} regressions"
                       + (f", slower: {html.escape(', '.join(gate['slower']))}" if gate["slower"] else ""))
        else:
            verdict = f"passed (against entries {', '.join(map(str, gate['against']))})"
        rows.append(f"<tr><td>{n}</td><td>{e['id']}</td><td>{html.escape(e['revision'])}</td>"
                    f"<td>{html.escape(e['date_utc'])}</td><td>{html.escape(m['cpu_model'])}, {m['hardware_threads']} threads "
                    f"({e['machine']})</td><td>{e['calibration_seconds']:.4g}</td><td>{e['runs']}</td>"
                    f"<td>{e['failures']}</td><td>{verdict}</td></tr>")
    return ("<table><tr><th>#</th><th>entry</th><th>revision</th><th>date (UTC)</th><th>machine</th>"
            "<th>calibration s</th><th>runs</th><th>failed jobs</th><th>gate</th></tr>" + "".join(rows) + "</table>")


def changes_table(suite):
    rows = []
    for label, g in sorted(suite["groups"].items()):
        for name, values in sorted(changed_metrics(g, suite["entries"]).items()):
            present = [(i, v) for i, v in enumerate(values) if v is not None]
            rows.append(f"<tr><td>{html.escape(label)}</td><td>{html.escape(name)}</td>"
                        f"<td>{present[0][1]:.6g} (#{present[0][0]})</td><td>{present[-1][1]:.6g} (#{present[-1][0]})</td></tr>")
    if not rows:
        return "<p>No metric of any group changed over these entries.</p>"
    return ("<table><tr><th>group</th><th>metric (sum over the group's runs)</th><th>first</th><th>last</th></tr>"
            + "".join(rows) + "</table>")


class Progress:
    """Figures drawn, on stderr: on a terminal one line rewritten in place with the time left, else
    a line at most every PLAIN_INTERVAL seconds and a last one (as bspbench's own progress lines)."""
    PLAIN_INTERVAL = 10

    def __init__(self, total):
        self.total, self.done = total, 0
        self.start = self.last = time.monotonic()
        self.terminal = sys.stderr.isatty()

    def step(self):
        self.done += 1
        now = time.monotonic()
        if self.terminal or now - self.last >= self.PLAIN_INTERVAL or self.done == self.total:
            self.last = now
            elapsed = now - self.start
            left = elapsed * (self.total - self.done) / self.done
            line = f"history: {self.done}/{self.total} figures, elapsed {elapsed:.0f} s, about {left:.0f} s left"
            end = "\n" if self.done == self.total or not self.terminal else ""
            sys.stderr.write(("\r\033[K" if self.terminal else "") + line + end)
            sys.stderr.flush()


def figures(suite):
    """(scene, labels) per figure: one per scene, split past PER_FIGURE groups."""
    by_scene = {}
    for label in sorted(suite["groups"]):
        by_scene.setdefault(scene_of(label), []).append(label)
    return [(scene, labels[part:part + PER_FIGURE]) for scene, labels in sorted(by_scene.items())
            for part in range(0, len(labels), PER_FIGURE)]


def render_suite(suite, out_dir, index, progress):
    entries = suite["entries"]
    parts = [f"<h2 id='{html.escape(suite['name'])}'>Suite {html.escape(suite['name'])}</h2>",
             f"<p>{len(entries)} entries, {len(suite['groups'])} timing groups, "
             f"{len(suite['machines'])} machine(s).</p>", entries_table(suite),
             "<h3>Metrics that changed</h3>", changes_table(suite), "<h3>Every group over the entries</h3>"]
    for k, (scene, labels) in enumerate(figures(suite)):
        png = f"history-{index}-{k}.png"
        draw_scene(labels, suite["groups"], entries, os.path.join(out_dir, png))
        parts.append(f"<h4>{html.escape(scene)}</h4><img src='{png}' alt='history of {html.escape(scene)}'>")
        progress.step()
    return "\n".join(parts)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    try:
        with open(args.data, encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        fail(f"{args.data}: {e}")
    if not isinstance(data, dict) or "suites" not in data:
        fail(f"{args.data}: not the data of bspbench history")
    os.makedirs(args.out, exist_ok=True)
    for old in os.listdir(args.out):
        if old.startswith("history-") and old.endswith(".png"):
            os.remove(os.path.join(args.out, old))
    progress = Progress(sum(len(figures(s)) for s in data["suites"]))
    body = "\n".join(render_suite(s, args.out, i, progress) for i, s in enumerate(data["suites"]))
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>bspbench history</title>
<style>body{{font-family:sans-serif;margin:2em;max-width:1800px}} table{{border-collapse:collapse;font-size:12px;margin:1em 0}}
td,th{{border:1px solid #ccc;padding:2px 6px;text-align:left}} img{{max-width:100%}}</style></head><body>
<h1>bspbench history</h1>
<p>From {html.escape(data['database'])}. The gate judges each entry against the last {data['last']} entries of its
suite and machine before it (bspbench regress --history): results as the newest, build times pooled.
Build times are each run's gated samples over their in-run reference, a geometric mean per group, drawn as a
ratio to the first entry of the same machine, a line per machine; a dotted rule marks a change of machine.</p>
{body}
</body></html>
"""
    tmp = os.path.join(args.out, "index.html.tmp")
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(page)
    os.replace(tmp, os.path.join(args.out, "index.html"))


if __name__ == "__main__":
    main()
