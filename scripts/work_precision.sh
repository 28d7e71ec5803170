#!/usr/bin/env bash
# Work precision: builds the driver (bench/work_precision.cpp, Release) and runs it.
# Writes work_precision.csv, work_precision.md (the tables, also printed) and
# work_precision.png into the build directory ($BUILD_DIR/work_precision), or into
# docs/ (docs/figures/ for the figure) with --update-docs, which rewrites the tracked
# files docs/benchmarks.md shows. A few minutes on 2 cores.
# Other arguments go to the driver: --quick (fewer resolutions), --out DIR, --benchmark_* flags.
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
out="$build/work_precision"
args=()
update_docs=false
for arg in "$@"; do
  if [ "$arg" = "--update-docs" ]; then update_docs=true; else args+=("$arg"); fi
done
$update_docs && out=docs
for ((i = 0; i < ${#args[@]}; ++i)); do
  [ "${args[i]}" = "--out" ] && [ $((i + 1)) -lt ${#args[@]} ] && out=${args[i + 1]}
done
mkdir -p "$out"
"$build/bench/work_precision" --out "$out" "${args[@]}"
png="$out/work_precision.png"
if [ "$out" = docs ]; then
  mkdir -p docs/figures
  png=docs/figures/work_precision.png
fi
gnuplot -e "csv='$out/work_precision.csv'; out='$png'" docs/figures/work_precision.gp
echo "wrote $out/work_precision.csv, $out/work_precision.md, $png"
