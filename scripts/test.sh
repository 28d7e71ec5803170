#!/usr/bin/env bash
# Installs what is missing, builds rigidity with its tests and runs them all.
# In CI (CI=true) warnings are errors.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B build-tests -DCMAKE_BUILD_TYPE=Release -DRIGIDITY_WERROR=$werror -DRIGIDITY_BUILD_BENCHMARKS=ON >/dev/null
cmake --build build-tests -j2
ctest --test-dir build-tests --output-on-failure -j2 --timeout 300
