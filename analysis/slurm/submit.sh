#!/usr/bin/env bash
# Runs a sweep on a Slurm cluster: a job array of N shards (sweep.sbatch), then one job that merges
# them and renders the report (merge.sbatch), which starts only when every shard succeeded. What a
# cluster user types, from the repository, on a filesystem the compute nodes share:
#
#   cmake --preset release && cmake --build --preset release
#   analysis/slurm/submit.sh --suite quick --shards 8 --out results/slurm-quick --cpus-per-task=4
#
# Results: OUT/merged.json and OUT/report/index.html; each shard's report is OUT/shard-i.json and
# the jobs' output is in OUT/logs. Options after --out (or after --) go to both sbatch calls as
# they are (--partition, --account, --time, --cpus-per-task, ...); --cpus-per-task is each shard's
# --threads. BSPBENCH names another binary than build/bspbench. Submitting the same command again
# (after a shard failed, was killed or ran out of time) resumes each shard from its journal: the
# jobs it finished are not run again by the same build.
#
# Prints "ARRAY_JOB_ID MERGE_JOB_ID" on stdout, and how to follow and resubmit on stderr.
set -euo pipefail

usage="usage: analysis/slurm/submit.sh --suite NAME --shards N --out DIR [SBATCH OPTION...]"
die() { echo "submit.sh: $*" >&2; exit 2; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)

suite= shards= out=
sbatch_options=()
while (($#)); do
  case $1 in
    --suite) suite=${2-}; shift 2 || die "--suite needs a value" ;;
    --shards) shards=${2-}; shift 2 || die "--shards needs a value" ;;
    --out) out=${2-}; shift 2 || die "--out needs a value" ;;
    -h | --help) echo "$usage"; exit 0 ;;
    --) shift; sbatch_options+=("$@"); break ;;
    *) sbatch_options+=("$1"); shift ;;
  esac
done
[[ -n $suite && -n $shards && -n $out ]] || die "needs --suite, --shards and --out ($usage)"
[[ $shards =~ ^[1-9][0-9]*$ ]] || die "--shards '$shards' is not a positive integer"
bspbench=${BSPBENCH:-$repo/build/bspbench}
[[ -x $bspbench ]] || die "$bspbench: not an executable (build it first: cmake --preset release && cmake --build --preset release)"
command -v sbatch >/dev/null || die "sbatch not found (is this a Slurm login node?)"
bspbench=$(realpath "$bspbench")
# A suite file (bspbench sweep reads --suite as a file when it ends in .json or holds a '/') is
# passed absolute, so a job that starts in another directory still finds it.
name=$(basename "$suite" .json)
if [[ $suite == *.json || $suite == */* ]]; then
  [[ -f $suite ]] || die "$suite: no such suite file"
  suite=$(realpath "$suite")
fi
# Absolute, since the jobs may start elsewhere; made now, since Slurm does not create the
# directories of --output.
mkdir -p "$out/logs"
out=$(realpath "$out")

# --parsable prints "ID" or "ID;CLUSTER".
array_id=$(sbatch --parsable --job-name="bspbench-$name" --array="0-$((shards - 1))" \
  --output="$out/logs/shard-%a.out" "${sbatch_options[@]}" \
  "$here/sweep.sbatch" --suite "$suite" --shards "$shards" --out "$out" --bspbench "$bspbench")
array_id=${array_id%%;*}
merge_id=$(sbatch --parsable --job-name="bspbench-$name-merge" --dependency="afterok:$array_id" \
  --output="$out/logs/merge.out" "${sbatch_options[@]}" \
  "$here/merge.sbatch" --shards "$shards" --out "$out" --bspbench "$bspbench")
merge_id=${merge_id%%;*}

cat >&2 <<MSG
submit.sh: shards: job array $array_id (tasks 0-$((shards - 1))); merge and report: job $merge_id, after all shards succeed
submit.sh: follow with: squeue -j $array_id,$merge_id
submit.sh: results: $out/merged.json and $out/report/index.html; logs: $out/logs
submit.sh: if a shard fails or is killed, the merge never starts (scancel $merge_id); the same submit.sh command again resumes every shard from its journal
MSG
echo "$array_id $merge_id"
