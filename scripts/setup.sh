#!/usr/bin/env bash
# Installs the Debian 12 packages softarm needs (only those missing, so a
# second run is near-instant), then configures and builds in ./build.
set -euo pipefail
cd "$(dirname "$0")/.."

# libopenblas0-pthread: CHOLMOD's supernodal Cholesky (3D meshes) spends its time in BLAS/LAPACK;
# without it Debian links the reference BLAS, 12x slower (Hex27, 61k dofs: 36.8 s vs 3.0 s per
# factorisation), and the threaded build is 1.7-2.2x faster than the serial one on 2 cores
# (bench_linear_solver; numbers in fem/solver/linear_solver.cpp). Installing it makes it the
# libblas.so.3/liblapack.so.3 alternative (priority 100) unless an admin has pinned another.
# libopenmpi-dev, openmpi-bin: `mpirun -np N softarm study …` spreads a study's points over
# machines (studies/cluster.hpp); the [study] tests check 2 ranks give the serial results.
# chromium: the [browser] tests render the HTML reports headless (tests/support/browser_render.hpp);
# about 120 MB download, 410 MB installed. Its fonts come with it (libfontconfig1 -> fontconfig-config
# -> fonts-dejavu-core), enough for the reports' text to lay out, so no font package is listed.
packages=(build-essential cmake libeigen3-dev libsuitesparse-dev libopenblas0-pthread libnlopt-cxx-dev
          coinor-libipopt-dev nlohmann-json3-dev catch2 libcli11-dev calculix-ccx chromium
          libopenmpi-dev openmpi-bin)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
