#!/usr/bin/env bash
# Runs `softarm design` on a requirements file with each optimiser algorithm at
# the same evaluation budget, two at a time, and prints one line per algorithm:
# real evaluations, cache hits, optimiser time, the optimum's objective and
# whether it meets every requirement (from each run's summary.json).
# Usage: scripts/compare_algorithms.sh [requirements.json] [budget] [output dir]
# (SOFTARM_BIN picks the binary, default build/softarm.)
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/thesis_requirements.json}
budget=${2:-60}
out=${3:-out/compare_algorithms}
algorithms=(nlopt:cobyla nlopt:auglag_bobyqa nlopt:isres nlopt:slsqp nlopt:ccsaq ipopt)
mkdir -p "$out"
run() {
  local a=$1 dir="$out/${1//:/_}"
  "${SOFTARM_BIN:-build/softarm}" design "$config" -o "$dir" --algorithm "$a" --max-evaluations "$budget" > "$dir.log" 2>&1 || true
}
for ((i = 0; i < ${#algorithms[@]}; i += 2)); do
  run "${algorithms[i]}" &
  [ $((i + 1)) -lt ${#algorithms[@]} ] && run "${algorithms[i + 1]}" &
  wait
done
printf '%-22s %6s %6s %9s %10s %9s %9s\n' algorithm evals hits time_s objective feasible payload_kg
for a in "${algorithms[@]}"; do
  f="$out/${a//:/_}/summary.json"
  [ -f "$f" ] || { echo "$a: no summary (see $out/${a//:/_}.log)"; continue; }
  python3 - "$a" "$f" <<'PY'
import json, sys
a, f = sys.argv[1], sys.argv[2]
s = json.load(open(f))
o = s["optimiser"]
m = s["optimum_measures"]
print(f'{a:<22} {o["evaluations"]:6d} {o["cache_hits"]:6d} {o["seconds"]:9.1f} {m["mass_kg"]:10.4f} {str(s["feasible"]):>9} {m["payload_kg"]:9.3f}')
PY
done
