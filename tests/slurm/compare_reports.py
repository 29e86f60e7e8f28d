#!/usr/bin/env python3
"""Whether two sweep reports agree in every deterministic field, as deterministic_view in
src/results/record.h defines them (the tests in C++ compare deterministic_view(a) == deterministic_view(b)).

  compare_reports.py A.json B.json      exit 0 when they agree, 1 (naming the first differences) when not
  compare_reports.py --self-check A.json
                                        exit 0 when the comparison catches a planted change of one run's
                                        result and ignores a planted change of its timings, 1 otherwise

The dropped keys are read from src/results/record.cpp, not copied here, so the two cannot drift apart.
Bad input (unreadable or non-JSON files, a record.cpp without the list) exits 2 with one line.
"""
import copy
import json
import os
import re
import sys

RECORD_CPP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "src", "results", "record.cpp")


def fail(message):
    print(f"compare_reports.py: {message}", file=sys.stderr)
    sys.exit(2)


def non_deterministic_keys():
    path = os.path.normpath(RECORD_CPP)
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    m = re.search(r"kNonDeterministicKeys\s*=\s*\{([^}]*)\}", text)
    keys = re.findall(r'"([^"]+)"', m.group(1)) if m else []
    if not keys:
        fail(f"{path}: no kNonDeterministicKeys list of quoted keys")
    return frozenset(keys)


def read(path):
    try:
        with open(path, encoding="utf-8") as f:
            report = json.load(f)
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        fail(f"{path}: not JSON ({e})")
    if not isinstance(report, dict) or not isinstance(report.get("runs"), list):
        fail(f"{path}: not a sweep report (no runs array)")
    return report


def differences(a, b, dropped, path="", out=None, limit=10):
    """Paths where the deterministic views of a and b differ (at most `limit`)."""
    out = [] if out is None else out
    if len(out) >= limit:
        return out
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted((a.keys() | b.keys()) - dropped):
            if k not in a or k not in b:
                out.append(f"{path}/{k}: only in {'the second' if k in b else 'the first'}")
            else:
                differences(a[k], b[k], dropped, f"{path}/{k}", out, limit)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path}: {len(a)} vs {len(b)} elements")
        for i, (x, y) in enumerate(zip(a, b)):
            differences(x, y, dropped, f"{path}/{i}", out, limit)
    # bool is an int in Python but never equal to a number in JSON (nor in nlohmann::json).
    elif a != b or isinstance(a, bool) != isinstance(b, bool):
        out.append(f"{path}: {json.dumps(a)[:80]} vs {json.dumps(b)[:80]}")
    return out[:limit]


def self_check(report, dropped):
    """The comparison must see a changed result and must not see a changed timing."""
    run = next((r for r in report["runs"] if isinstance(r.get("metrics"), dict) and isinstance(r.get("timings"), dict)
                and any(isinstance(v, (int, float)) and not isinstance(v, bool) for v in r["metrics"].values())), None)
    if run is None:
        print("compare_reports.py: self-check: no run with numeric metrics and timings to plant a change in")
        return False
    index = report["runs"].index(run)
    metric = next(k for k, v in run["metrics"].items() if isinstance(v, (int, float)) and not isinstance(v, bool))
    changed = copy.deepcopy(report)
    changed["runs"][index]["metrics"][metric] += 1
    seen = differences(report, changed, dropped)
    retimed = copy.deepcopy(report)
    for k, v in retimed["runs"][index]["timings"].items():
        retimed["runs"][index]["timings"][k] = [2 * x for x in v] if isinstance(v, list) else 2 * v if isinstance(v, (int, float)) else v
    retimed["runs"][index]["timings"]["planted_seconds"] = 1.0
    unseen = differences(report, retimed, dropped)
    ok = seen == [f"/runs/{index}/metrics/{metric}: {json.dumps(run['metrics'][metric])} vs "
                  f"{json.dumps(changed['runs'][index]['metrics'][metric])}"] and not unseen
    print(f"compare_reports.py: self-check: a change of runs[{index}].metrics.{metric} "
          f"{'is caught' if seen else 'is MISSED'}; a change of its timings {'is ignored' if not unseen else 'is REPORTED'}")
    return ok


def main(argv):
    dropped = non_deterministic_keys()
    if len(argv) == 2 and argv[0] == "--self-check":
        return 0 if self_check(read(argv[1]), dropped) else 1
    if len(argv) != 2 or argv[0].startswith("-"):
        fail("usage: compare_reports.py A.json B.json | --self-check A.json")
    a, b = read(argv[0]), read(argv[1])
    diffs = differences(a, b, dropped)
    if diffs:
        print(f"compare_reports.py: {argv[0]} and {argv[1]} differ in deterministic fields (ignoring "
              f"{', '.join(sorted(dropped))}), first differences:")
        for d in diffs:
            print(f"  {d}")
        return 1
    print(f"compare_reports.py: {argv[0]} and {argv[1]} agree in every deterministic field "
          f"({len(a['runs'])} runs; ignoring {', '.join(sorted(dropped))})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
