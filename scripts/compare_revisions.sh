#!/usr/bin/env bash
# Before/after check of a change: runs the thesis RRA, 3CA and SPL scenes and a short design with two
# builds of softarm and compares every result they write, number by number (build/tests/compare_outputs,
# tests/support/output_comparison.hpp: relative tolerance 1e-6, times skipped).
#
#   scripts/compare_revisions.sh [--quick] [--rtol R] [--threads N] OLD [NEW]
#
# OLD and NEW are git revisions (built once each in a worktree under $SOFTARM_COMPARE_DIR, default
# /tmp/softarm-compare, and reused) or paths to softarm binaries; NEW defaults to this checkout's
# build/softarm (built here). Each runs the configs of its own source tree. --quick leaves out the SPL
# (about 4 minutes on 2 cores; the RRA takes a second, the 3CA about a minute, the design about one).
# Exit 0 when every result agrees, 1 when one differs (the differences are listed), 2 on bad usage.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$(pwd)

quick=0 rtol=1e-6 threads=$(nproc 2>/dev/null || echo 2)
args=()
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --rtol) rtol=${2:?--rtol needs a value}; shift ;;
    --threads) threads=${2:?--threads needs a value}; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    -*) echo "compare_revisions: unknown option '$1'" >&2; exit 2 ;;
    *) args+=("$1") ;;
  esac
  shift
done
if ((${#args[@]} < 1 || ${#args[@]} > 2)); then
  echo "usage: scripts/compare_revisions.sh [--quick] [--rtol R] [--threads N] OLD [NEW]" >&2
  exit 2
fi
work=${SOFTARM_COMPARE_DIR:-/tmp/softarm-compare}
mkdir -p "$work/out"

# The softarm binary for a revision or a binary path, built if need be (stdout: the binary).
binary_of() {
  local what=$1
  if [ -x "$what" ] && [ -f "$what" ]; then
    readlink -f "$what"
    return
  fi
  local sha
  sha=$(git rev-parse --verify --quiet "$what^{commit}") || { echo "compare_revisions: '$what' is neither a binary nor a git revision" >&2; exit 2; }
  local tree="$work/src-${sha:0:12}"
  [ -d "$tree" ] || git worktree add --detach --force "$tree" "$sha" >&2
  if [ ! -x "$tree/build/softarm" ]; then
    echo "compare_revisions: building ${sha:0:12} in $tree/build" >&2
    cmake -S "$tree" -B "$tree/build" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$tree/build" -j"$threads" --target softarm >&2
  fi
  echo "$tree/build/softarm"
}

# This checkout's build: the comparison tool, and softarm itself when NEW is left out.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
new_arg=${args[1]:-}
if [ -z "$new_arg" ]; then
  cmake --build build -j"$threads" --target softarm >&2
  new_arg=build/softarm
fi
cmake --build build -j"$threads" --target compare_outputs >&2
old_bin=$(binary_of "${args[0]}")
new_bin=$(binary_of "$new_arg")

# The source tree whose configs a binary runs: the one above its build folder, if it has configs/.
tree_of() {
  local above
  above=$(dirname "$(dirname "$1")")
  if [ -d "$above/configs" ]; then echo "$above"; else echo "$repo"; fi
}

runs=("rra:simulate configs/rra_thesis.json" "tca:simulate configs/tca_thesis.json")
((quick)) || runs+=("spl:simulate configs/spl_thesis_pose.json")
runs+=("design:design configs/thesis_requirements.json --fidelity fast --max-evaluations 3 --fresh")

status=0
for run in "${runs[@]}"; do
  name=${run%%:*} command=${run#*:}
  for side in old new; do
    bin=$old_bin
    [ "$side" = new ] && bin=$new_bin
    out="$work/out/$side/$name"
    rm -rf "$out"
    start=$(date +%s)
    (cd "$(tree_of "$bin")" && "$bin" --threads "$threads" $command -o "$out" >"$work/out/$side-$name.log" 2>&1) ||
      echo "compare_revisions: $side $name exited $? (log: $work/out/$side-$name.log)"
    echo "$side $name: $(($(date +%s) - start)) s"
  done
  build/tests/compare_outputs "$work/out/old/$name" "$work/out/new/$name" --rtol "$rtol" || status=1
done
((status == 0)) && echo "compare_revisions: every result agrees within rtol $rtol" ||
  echo "compare_revisions: results differ (above)"
exit $status
