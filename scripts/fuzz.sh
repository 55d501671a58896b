#!/usr/bin/env bash
# Fuzzes every input reader with libFuzzer (issue 35): tests/fuzz/fuzz_<reader>.cpp.
#
#   scripts/fuzz.sh                      # every reader, 600 s each (two at a time on 2 cores)
#   scripts/fuzz.sh 60 uniaxial_csv      # one reader for a minute
#
# Readers: scene_config, material, uniaxial_csv, design_config, study. Each must take any bytes to
# a validated value or an InputError (tests/fuzz/fuzz_reader.hpp); every library is built with
# clang, AddressSanitizer and UndefinedBehaviorSanitizer in build-fuzz/. Seeds come from configs/
# and the Treloar data; the corpus grows in build-fuzz/corpus/<reader> (a rerun continues from it),
# and what crashes, hangs (10 s per input), leaks or exceeds 2 GB is written to
# build-fuzz/findings/<reader>/. Prints each reader's executions and findings; exit 1 on any finding.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-600}
shift || true
readers=("$@")
((${#readers[@]})) || readers=(scene_config material uniaxial_csv design_config study)
[[ "$seconds" =~ ^[1-9][0-9]*$ ]] || { echo "fuzz.sh: seconds per reader must be a positive integer, got '$seconds'" >&2; exit 2; }
for r in "${readers[@]}"; do
  [ -f "tests/fuzz/fuzz_$r.cpp" ] || { echo "fuzz.sh: unknown reader '$r' (known: scene_config material uniaxial_csv design_config study)" >&2; exit 2; }
done

# clang and its libFuzzer runtime (Debian 12: clang-14, libclang-rt-14-dev), if missing.
missing=()
for p in clang libclang-rt-14-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only" -DSOFTARM_FUZZ=ON \
  -DBUILD_TESTING=OFF >/dev/null
cmake --build build-fuzz -j"$jobs" --target "${readers[@]/#/fuzz_}"

# Seeds: the shipped configs each reader reads.
seed() {  # seed <reader> <files...>
  local r=$1
  shift
  mkdir -p "build-fuzz/seeds/$r"
  cp "$@" "build-fuzz/seeds/$r/"
}
seed scene_config configs/rra_thesis.json configs/tca_thesis.json configs/spl_thesis_pose.json configs/convergence/*.json
seed design_config configs/thesis_requirements.json
seed study configs/studies/*.json
mkdir -p build-fuzz/seeds/uniaxial_csv
printf 'stretch,nominal_stress_MPa\n# Dragon Skin 30, a few points\n1.0,0\n1.5,0.08\n2.0,0.13\n3.0,0.22\n' \
  >build-fuzz/seeds/uniaxial_csv/small.csv
[ ! -f ../shared/data/treloar1944/uniaxial.csv ] || cp ../shared/data/treloar1944/uniaxial.csv build-fuzz/seeds/uniaxial_csv/
mkdir -p build-fuzz/seeds/material
printf '"dragon_skin_30"' >build-fuzz/seeds/material/builtin.json
printf '{"name": "ds30_fit", "law": "ogden", "mu_MPa": [0.1153, -0.0115], "alpha": [2.52, -2.0], "D_per_MPa": [0.7029], "density_g_cm3": 1.08, "tensile_strength_MPa": 3.45, "elongation_at_break_percent": 364}' \
  >build-fuzz/seeds/material/ogden.json
printf '{"name": "nh", "law": "neo_hookean", "mu_MPa": [0.2], "D_per_MPa": [0.5], "density_g_cm3": 1.1}' \
  >build-fuzz/seeds/material/neo_hookean.json

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
run_one() {  # run_one <reader>: the fuzzer's log in build-fuzz/findings/<reader>.log
  local r=$1
  mkdir -p "build-fuzz/corpus/$r" "build-fuzz/findings/$r"
  "build-fuzz/tests/fuzz/fuzz_$r" "build-fuzz/corpus/$r" "build-fuzz/seeds/$r" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/findings/$r/" >"build-fuzz/findings/$r.log" 2>&1 || true
}
pids=()
for r in "${readers[@]}"; do
  run_one "$r" &
  pids+=($!)
  if ((${#pids[@]} >= jobs)); then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
done
wait

status=0
printf '%-14s %10s %12s %8s %9s\n' reader seconds executions corpus findings
for r in "${readers[@]}"; do
  log="build-fuzz/findings/$r.log"
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  corpus=$(find "build-fuzz/corpus/$r" -type f | wc -l)
  found=$(find "build-fuzz/findings/$r" -type f | wc -l)
  printf '%-14s %10s %12s %8s %9s\n' "$r" "$seconds" "${execs:-?}" "$corpus" "$found"
  if ((found > 0)) || ! grep -q 'Done [0-9]* runs' "$log"; then
    status=1
    echo "  $r: see $log and build-fuzz/findings/$r/" >&2
  fi
done
exit $status
