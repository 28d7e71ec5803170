#!/usr/bin/env bash
# Installs what is missing, builds rigidity (Release) and runs the main job:
# `rigidity run` on the embedded default scene, the paper's wall impact.
# Extra arguments go to `rigidity run` (e.g. configs/hooke_wall_impact.yaml --out out/hooke).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DRIGIDITY_BUILD_TESTS=OFF -DRIGIDITY_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build --target rigidity -j2
./build/rigidity run "$@"
