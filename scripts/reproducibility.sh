#!/usr/bin/env bash
# Is `softarm design`'s answer the same whatever the machine does with it? Runs the main job on a
# requirements file twice, one after the other, each in its own output directory:
#   A: SOFTARM_THREADS=1, OPENBLAS_CORETYPE=${CORE_A:-Haswell}
#   B: SOFTARM_THREADS=2, OPENBLAS_CORETYPE=${CORE_B:-SkylakeX where the processor has AVX-512, else
#      Sandybridge} (a forced kernel is not checked against the processor: SkylakeX on a machine
#      without AVX-512 dies of an illegal instruction, so the default asks /proc/cpuinfo)
# and prints the two answers side by side with the issue's test of "the same answer": equal
# integers and materials, continuous variables within 0.5 % of their range, mass within 0.5 %,
# the same verdict on the accurate model.
# Usage: scripts/reproducibility.sh [requirements.json] [output dir] [extra softarm design options...]
# (SOFTARM_BIN picks the binary, default build/softarm; BOTH_AT_ONCE=1 runs A and B side by side,
# which changes their times, not their answers.) Exit 0 when the answers agree, 1 when not.
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/thesis_requirements.json}
out=${2:-out/reproducibility}
shift $(($# > 2 ? 2 : $#)) || true
mkdir -p "$out"
bin=${SOFTARM_BIN:-build/softarm}
run() {  # name threads coretype [softarm design options...]
  local name=$1 threads=$2 core=$3
  shift 3
  echo "run $name: SOFTARM_THREADS=$threads OPENBLAS_CORETYPE=$core ($out/$name.log)"
  # OPENBLAS_VERBOSE=2: the log's first line names the kernel OpenBLAS took ("Core: Haswell").
  OPENBLAS_VERBOSE=2 SOFTARM_THREADS=$threads OPENBLAS_CORETYPE=$core "$bin" design "$config" -o "$out/$name" --fresh "$@" \
    > "$out/$name.log" 2>&1 || true
}
extra=("$@")
default_b=Sandybridge
grep -qw avx512f /proc/cpuinfo 2>/dev/null && default_b=SkylakeX
if [[ "${BOTH_AT_ONCE:-0}" == 1 ]]; then
  run A 1 "${CORE_A:-Haswell}" "${extra[@]}" &
  run B 2 "${CORE_B:-$default_b}" "${extra[@]}" &
  wait
else
  run A 1 "${CORE_A:-Haswell}" "${extra[@]}"
  run B 2 "${CORE_B:-$default_b}" "${extra[@]}"
fi
python3 - "$config" "$out/A/summary.json" "$out/B/summary.json" <<'PY'
import json, re, sys
config_file, fa, fb = sys.argv[1:4]
text = open(config_file).read()
config = json.loads(re.sub(r"^\s*//.*$", "", text, flags=re.M))
space = config["design_space"]
a, b = json.load(open(fa)), json.load(open(fb))
same = True
print(f'{"":34} {"A":>16} {"B":>16}  same')
for name, bounds in space.items():
    va, vb = a["optimum"][name], b["optimum"][name]
    if "choices" in bounds or name == "ring_count":
        ok = va == vb
    else:
        ok = abs(va - vb) <= 0.005 * (bounds["max"] - bounds["min"])
    same &= ok
    fmt = lambda v: f"{v:16.6g}" if isinstance(v, (int, float)) else f"{v:>16}"
    print(f"{name:34} {fmt(va)} {fmt(vb)}  {'yes' if ok else 'NO'}")
ma, mb = a["optimum_measures"]["mass_kg"], b["optimum_measures"]["mass_kg"]
ok = abs(ma - mb) <= 0.005 * max(ma, mb)
same &= ok
print(f'{"mass_kg":34} {ma:16.6g} {mb:16.6g}  {"yes" if ok else "NO"}')
for key in ("feasible",):
    ok = a[key] == b[key]
    same &= ok
    print(f'{key + " (accurate model)":34} {str(a[key]):>16} {str(b[key]):>16}  {"yes" if ok else "NO"}')
for s, name in ((a, "A"), (b, "B")):
    v = s.get("verification")
    if v:
        print(f"{name}: verified payload {v['measures']['payload_kg']:.4f} kg, all_met {v['all_met']}, {s['seconds']:.0f} s")
print("the same answer" if same else "DIFFERENT answers")
sys.exit(0 if same else 1)
PY
