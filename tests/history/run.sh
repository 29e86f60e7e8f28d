#!/usr/bin/env bash
# Results over time (ctest's history_*): a history database of five entries made by real sweeps of a
# small suite, three at "revisions" r1..r3 (each report's revision rewritten, as three commits would
# make them), r4 with crystal's builds slowed 3x (BSPBENCH_PLANT_SLOWDOWN), r5 on "another machine"
# (its processor rewritten). Checks:
#   - regress --history judges a clean run as passing and the planted run as failing, against the
#     pooled last entries of the same suite and machine, and an appended report by those before it;
#   - bspbench history draws the page (DIR, for the browser test) and its data say what the page
#     marks: r4 failed with crystal's group slower, r5 not judged (a new machine: a break);
#   - bad databases and reports: one line, exit 2, nothing appended or written.
# Usage: run.sh BSPBENCH WORK_DIR PAGE_DIR
set -euo pipefail
exe=$1 work=$2 page=$3
rm -rf "$work" "$page"
mkdir -p "$work"
fail() { echo "history: $*" >&2; exit 1; }
cat >"$work/suite.json" <<'JSON'
{"name": "history-test", "blocks": [{"scenes": ["random-triangles"], "sizes": [200, 400], "seeds": [1, 2, 3],
 "heuristics": ["first", "crystal"], "validation": {"views": 1}}]}
JSON
sweep() {  # sweep OUT [env...]: a fresh sweep of the suite into OUT
  local out=$1; shift
  env "$@" "$exe" sweep --suite "$work/suite.json" --fresh --threads 1 --out "$out" --journal-dir "$work/journal" >/dev/null 2>&1
}
edit() {  # edit FILE PYTHON-EXPRESSION-ON-r
  /usr/bin/python3 -c "import json,sys; r=json.load(open(sys.argv[1])); $2; json.dump(r, open(sys.argv[1],'w'))" "$1"
}
for i in 1 2 3; do
  sweep "$work/r$i.json"
  edit "$work/r$i.json" "r['shards'][0]['environment']['git_revision'] = 'r$i-0000000000'"
done
sweep "$work/r4.json" BSPBENCH_PLANT_SLOWDOWN=crystal:3
edit "$work/r4.json" "r['shards'][0]['environment']['git_revision'] = 'r4-0000000000'"
sweep "$work/r5.json"
edit "$work/r5.json" "r['shards'][0]['environment']['git_revision'] = 'r5-0000000000'; r['shards'][0]['environment']['cpu_model'] = 'Another CPU'"
sweep "$work/clean.json"

db="$work/history.sqlite"
"$exe" history --db "$db" --append "$work/r1.json" --append "$work/r2.json" --append "$work/r3.json"
"$exe" regress --history "$db" --current "$work/clean.json" --last 3 || fail "a clean run failed against the history"
if "$exe" regress --history "$db" --current "$work/r4.json" --last 3 >"$work/regress_r4.log"; then
  fail "the planted 3x slowdown of crystal passed the gate against the history"
fi
grep -q "crystal" "$work/regress_r4.log" || fail "the failing regress does not name crystal: $(cat "$work/regress_r4.log")"
"$exe" history --db "$db" --append "$work/r4.json" --append "$work/r5.json" --out "$page" --last 3
[[ -f $page/index.html ]] || fail "no page"
# A report appended already is judged by the entries before it only, not by itself or later ones.
"$exe" regress --history "$db" --current "$work/r3.json" --last 3 >"$work/regress_r3.log" || fail "r3 failed against r1, r2"
grep -q "against 2 entries of .*: 1 (r1-0000000000) 2 (r2-0000000000)$" "$work/regress_r3.log" ||
  fail "r3 was not judged by r1 and r2 alone: $(head -1 "$work/regress_r3.log")"
/usr/bin/python3 - "$page/history.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
s = d["suites"][0]
e = s["entries"]
assert [x["revision"][:2] for x in e] == ["r1", "r2", "r3", "r4", "r5"], [x["revision"] for x in e]
assert not e[0]["gate"]["judged"] and e[1]["gate"]["judged"] and not e[2]["gate"]["failed"], e[:3]
assert e[3]["gate"]["failed"] and any("crystal" in g for g in e[3]["gate"]["slower"]), e[3]["gate"]
assert not e[4]["gate"]["judged"] and e[4]["machine"] != e[3]["machine"], e[4]
assert len(s["machines"]) == 2 and len(s["groups"]) == 2, s["groups"].keys()
print("history: page data as expected:", len(e), "entries,", len(s["groups"]), "groups")
PY

# Bad input: one line naming the file, exit 2, nothing written.
expect_exit2() {  # expect_exit2 WORD COMMAND...
  local word=$1; shift
  local code=0
  "$@" >"$work/out.log" 2>"$work/err.log" || code=$?
  [[ $code == 2 ]] || fail "exit $code, not 2, for: $* ($(cat "$work/err.log"))"
  [[ $(wc -l <"$work/err.log") == 1 ]] || fail "not one line for: $*: $(cat "$work/err.log")"
  grep -q -- "$word" "$work/err.log" || fail "no '$word' in: $(cat "$work/err.log")"
}
echo "not a database" >"$work/text.sqlite"
expect_exit2 "text.sqlite: file is not a database" "$exe" history --db "$work/text.sqlite" --out "$work/p1"
[[ ! -e $work/p1 ]] || fail "a page written from a bad database"
/usr/bin/python3 -c "import sqlite3,sys; c=sqlite3.connect(sys.argv[1]); c.execute('create table t(x)'); c.commit()" "$work/other.sqlite"
expect_exit2 "not a bspbench history" "$exe" history --db "$work/other.sqlite" --append "$work/r1.json"
expect_exit2 "no such history database" "$exe" regress --history "$work/missing.sqlite" --current "$work/r1.json"
expect_exit2 "text.sqlite" "$exe" sweep --suite "$work/suite.json" --history "$work/text.sqlite" --out "$work/never.json"
[[ ! -e $work/never.json ]] || fail "a sweep ran with a bad history database"
edit "$work/r1.json" "r['shards'][0]['count'] = 2"
before=$(/usr/bin/python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*) from sweeps').fetchone()[0])" "$db")
expect_exit2 "one shard of 2" "$exe" history --db "$db" --append "$work/r2.json" --append "$work/r1.json"
after=$(/usr/bin/python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('select count(*) from sweeps').fetchone()[0])" "$db")
[[ $before == "$after" ]] || fail "a failed append left $((after - before)) entries"
expect_exit2 "no earlier entry" "$exe" regress --history "$db" --current "$work/r5.json"
echo "history: regress --history, the page's data and 6 bad inputs as expected"
