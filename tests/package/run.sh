#!/usr/bin/env bash
# The installed package, as a user meets it (ctest's package_plugin_sweep):
#   1. `cmake --install` into a temporary prefix; no public header includes CGAL or Embree;
#   2. another project (consumer/) finds the package, includes every installed header in one file,
#      links bspbench::bsp and builds a tree; asking for another major.minor version fails;
#   3. examples/my_heuristic is built against the prefix, swept beside built-ins with --plugin,
#      gated against its own report, and the HTML report shows it.
# Usage: run.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 source=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
fail() { echo "package: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log"
headers=$(find "$work/prefix/include/bspbench" -name '*.h' | wc -l)
((headers > 50)) || fail "only $headers headers installed"
if grep -rlE '#include *[<"](CGAL|embree3)/' "$work/prefix/include"; then
  fail "the public headers above include CGAL or Embree"
fi

cmake -S "$source/tests/package/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DBSPBENCH_HEADERS="$work/prefix/include/bspbench" >"$work/consumer.log"
cmake --build "$work/consumer" -j2 >>"$work/consumer.log" || { cat "$work/consumer.log"; fail "the consumer does not build"; }
"$work/consumer/consumer" || fail "the consumer's tree is wrong"
if cmake -S "$source/tests/package/consumer" -B "$work/consumer_next" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DBSPBENCH_WANTED=0.2 >"$work/consumer_next.log" 2>&1; then
  fail "find_package(bspbench 0.2) accepted version $(grep -o 'VERSION [0-9.]*' "$build/CMakeCache.txt" | head -1)"
fi

cmake -S "$source/examples/my_heuristic" -B "$work/plugin" -DCMAKE_PREFIX_PATH="$work/prefix" >"$work/plugin.log"
cmake --build "$work/plugin" >>"$work/plugin.log" || { cat "$work/plugin.log"; fail "the example plugin does not build"; }
plugin="$work/plugin/libmy_heuristic.so"
"$build/bspbench" sweep --plugin "$plugin" --suite "$source/examples/my_heuristic/suite.json" --fresh \
  --out "$work/report.json" --journal-dir "$work/journal"
# Every largest_first run (2 labels x 5 scene sizes x 2 seeds) built, checked and validated by rays.
runs=$(python3 -c "import json,sys; r=json.load(open(sys.argv[1])); \
print(sum(x['id']['heuristic'].startswith('largest_first') and x['invariants']['violations'] == 0 and \
x['validation']['violations'] == 0 and x['validation']['rays'] > 0 for x in r['runs']))" "$work/report.json")
[[ $runs == 20 ]] || fail "$runs validated largest_first runs, not 20"
"$build/bspbench" regress --plugin "$plugin" --baseline "$work/report.json" --current "$work/report.json"
"$build/bspbench" report --plugin "$plugin" --in "$work/report.json" --out "$work/html"
grep -q 'largest_first:k=1' "$work/html/index.html" || fail "the HTML report does not show largest_first"
echo "package: $headers headers; consumer and plugin built against $work/prefix; $runs largest_first runs validated"
