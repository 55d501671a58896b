#!/usr/bin/env bash
# Builds softarm and its tests with AddressSanitizer and UndefinedBehaviorSanitizer (GCC, -O2 with
# debug lines) in build-sanitize/ and runs the test suite on that build (issue 35).
#
#   scripts/sanitize.sh                    # the whole suite
#   scripts/sanitize.sh -L cli             # ctest options pass through: here the CLI tests only
#   scripts/sanitize.sh --log F -L long    # one test at a time, each result appended to F as it
#                                          # ends; run again, it skips the tests F has as passed
#
# Any sanitizer report fails its test: ASan aborts on the first error (and on a leak at exit), UBSan
# halts on the first undefined behaviour, each with a stack trace in the test's output. Leaks inside
# Open MPI's own start-up (libmpi, libopen-pal, libopen-rte, hwloc, libevent: allocated once per
# process and never freed by design) are suppressed by library name; a leak in softarm's code is not.
# Expect the suite to take 3-6 times as long as in build/ (tests/support/time_limit.hpp).
set -euo pipefail
log=
if [[ "${1:-}" == "--log" ]]; then
  log=$(realpath -m "${2:?--log needs a file}")
  shift 2
fi
cd "$(dirname "$0")/.."

jobs=$(nproc 2>/dev/null || echo 2)
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
cmake --build build-sanitize -j"$jobs" --target softarm softarm_tests

suppressions=build-sanitize/lsan.supp
printf 'leak:%s\n' libmpi.so libopen-pal.so libopen-rte.so libhwloc.so libevent > "$suppressions"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export LSAN_OPTIONS=suppressions=$PWD/$suppressions:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Open MPI's plugins (mca_*.so, PMIx) are built without frame pointers, so the fast unwinder gives their
# allocations two-frame stacks that name no library and escape the suppressions above (a test's
# two ranks then fail on ~115 kB of Open MPI's own start-up at exit). The ranks started through this
# mpirun unwind every allocation fully instead; softarm's own leaks are still reported, with the
# whole stack. The rest of the suite keeps the fast unwinder.
wrapper=$PWD/build-sanitize/mpirun-wrapper/mpirun
if real_mpirun=$(command -v mpirun) && [[ $real_mpirun != "$wrapper" ]]; then
  mkdir -p build-sanitize/mpirun-wrapper
  printf '#!/bin/sh\nASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0" exec %s "$@"\n' "$real_mpirun" \
    > "$wrapper"
  chmod +x "$wrapper"
  export PATH=$PWD/build-sanitize/mpirun-wrapper:$PATH
fi
# The same work takes 3-6x longer here: the limits the tests put on the commands they start (mpirun)
# and ctest's default per-test limit (1,500 s) are scaled to match.
export SOFTARM_TEST_TIME_SCALE=${SOFTARM_TEST_TIME_SCALE:-6}
if [[ -z $log ]]; then
  exec ctest --test-dir build-sanitize --output-on-failure -j"$jobs" --timeout 9000 "$@"
fi
# The whole suite here takes hours: with --log each test's result is kept as it ends (passed/skipped/failed,
# name, seconds; the last failure's output in F.last-failure), and a rerun picks up where it stopped.
touch "$log"
status=0
while IFS= read -r name; do
  grep -qxF "passed"$'\t'"$name" <(cut -f1,2 "$log") && continue
  start=$SECONDS
  # By its whole name: the numbers `ctest -N` prints are renumbered under -E, so `-I N,N` would run
  # another test.
  pattern="^$(printf '%s' "$name" | sed 's/[][\\.*^$(){}?+|]/\\&/g')\$"
  # stdin from /dev/null: the loop reads the test names from stdin, and mpirun (the MPI tests) would
  # read the rest of them as its own input, ending the loop after that test as if all had run.
  if ctest --test-dir build-sanitize --output-on-failure -R "$pattern" --timeout 9000 >"$log.out" 2>&1 </dev/null; then
    result=passed
    grep -q '\*\*\*Skipped' "$log.out" && result=skipped  # its tool missing: run again next time
  else
    result=failed status=1
    cp "$log.out" "$log.last-failure"
  fi
  printf '%s\t%s\t%d s\n' "$result" "$name" $((SECONDS - start)) >>"$log"
done < <(ctest --test-dir build-sanitize -N "$@" | sed -n 's/^ *Test *#[0-9]*: \(.*\)$/\1/p')
rm -f "$log.out"
exit $status
