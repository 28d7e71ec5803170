#!/usr/bin/env bash
# Work precision: builds the driver (bench/work_precision.cpp, Release) and runs it.
# Writes docs/work_precision.csv, docs/work_precision.md (the tables, also printed) and
# docs/figures/work_precision.png (docs/figures/work_precision.gp). A few minutes on 2 cores.
# Arguments go to the driver: --quick (fewer resolutions), --out DIR, --benchmark_* flags.
# BUILD_DIR (default build-wp) is the build directory; in CI (CI=true) warnings are errors.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build=${BUILD_DIR:-build-wp}
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DRIGIDITY_WERROR=$werror -DRIGIDITY_BUILD_TESTS=OFF \
      -DRIGIDITY_BUILD_BENCHMARKS=ON >/dev/null
cmake --build "$build" --target work_precision -j"$(nproc)"
out=docs
args=("$@")
for ((i = 0; i < ${#args[@]}; ++i)); do
  [ "${args[i]}" = "--out" ] && [ $((i + 1)) -lt ${#args[@]} ] && out=${args[i + 1]}
done
mkdir -p "$out" docs/figures
"$build/bench/work_precision" --out "$out" "$@"
png=docs/figures/work_precision.png
[ "$out" = docs ] || png="$out/work_precision.png"
gnuplot -e "csv='$out/work_precision.csv'; out='$png'" docs/figures/work_precision.gp
echo "wrote $out/work_precision.csv, $out/work_precision.md, $png"
