#!/usr/bin/env bash
# Runs one libFuzzer target over its committed corpus: tests/fuzz/run.sh TARGET SECONDS [RUNS].
# BSPBENCH_FUZZ_SEED fixes libFuzzer's random seed (default 0: a new one each run); with a RUNS
# count too, a run is repeatable, which is how CI runs it.
# TARGET is mesh_reader, polygon_split, tree_build, report or exact_split; the binaries come from the `fuzz`
# preset (cmake --preset fuzz && cmake --build --preset fuzz). New inputs that reach new coverage
# go to build-fuzz/corpus/TARGET (a seeded run's to a temporary directory), not into the committed
# corpus; a crash leaves its input in build-fuzz/artifacts/ and fails the script.
set -euo pipefail
repo=$(cd "$(dirname "$0")/../.." && pwd)
target=${1:?usage: run.sh TARGET SECONDS [RUNS]}
seconds=${2:?usage: run.sh TARGET SECONDS [RUNS]}
runs=${3:--1}
binary="$repo/build-fuzz/fuzz_$target"
[[ -x $binary ]] || { echo "run.sh: $binary missing: cmake --preset fuzz && cmake --build --preset fuzz" >&2; exit 2; }
work="$repo/build-fuzz/corpus/$target"
# A seeded run starts from the committed corpus alone: finds left in build-fuzz/corpus by earlier
# runs would change what it tries, and then the same seed would not repeat the same inputs.
if [[ ${BSPBENCH_FUZZ_SEED:-0} != 0 ]]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work" "$repo/build-fuzz/artifacts"
# -rss_limit_mb: a reader that allocates what a file's header claims instead of what it holds is
# caught long before the machine runs out of memory. -max_len: the seeds are under 3 KB; longer
# inputs only slow the search down.
"$binary" "$work" "$repo/tests/fuzz/corpus/$target" -max_total_time="$seconds" -runs="$runs" \
  -seed="${BSPBENCH_FUZZ_SEED:-0}" -max_len=4096 -rss_limit_mb=1024 -malloc_limit_mb=512 -timeout=10 -print_final_stats=1 \
  -artifact_prefix="$repo/build-fuzz/artifacts/$target-"
