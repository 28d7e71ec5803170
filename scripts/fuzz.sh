#!/usr/bin/env bash
# Builds the test suite with clang under AddressSanitizer and UndefinedBehaviorSanitizer,
# runs it, then fuzzes the scene loader for a bounded time (FUZZ_SECONDS, default 60)
# from the committed seed corpus (fuzz/corpus, configs/, tests/scenes/invalid/).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh clang libclang-rt-14-dev
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
CC=clang CXX=clang++ cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRIGIDITY_SANITIZERS=ON \
  -DRIGIDITY_BUILD_FUZZERS=ON -DRIGIDITY_BUILD_BENCHMARKS=OFF -DRIGIDITY_BUILD_PYTHON=OFF >/dev/null
cmake --build build-sanitize -j2
ctest --test-dir build-sanitize --output-on-failure -j2 --timeout 600 -LE install
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus"
cp fuzz/corpus/* configs/*.yaml tests/scenes/invalid/* "$work/corpus/"
./build-sanitize/fuzz/scene_loader_fuzzer "$work/corpus" -max_total_time="${FUZZ_SECONDS:-60}" -max_len=65536 \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$work/" 2>&1 | tail -n 15
