#!/usr/bin/env bash
# The mutation check: the test suite must notice each physics mutation of
# scripts/mutations.txt (a factor in a material law, the shock jump conditions, the wall
# reflection, the fan step, the contact rule, the energy bookkeeping).
#
# Copies the tree (tracked and untracked, not ignored, files) to a scratch directory,
# builds the test executables the mutations name once, then for each mutation: replaces
# its search text (which must occur exactly once), rebuilds those executables
# incrementally, runs the tests it names and requires at least one to fail, and restores
# the file. Exits non-zero if a mutation is missed, does not apply or does not build.
#
#   scripts/mutation_check.sh [MUTATIONS_FILE]       JOBS=2 by default
#   MUTATIONS_CHECK_ONLY=1 scripts/mutation_check.sh   only that every search text applies
#   MUTATIONS_BUILD=build-tests scripts/mutation_check.sh
#       mutates the tree in place and rebuilds in that (configured and built) build directory
#       instead of a copy: CI, whose clean clone scripts/test.sh has just built, saves the copy's
#       build. Every file is restored as it was, on any exit. The mutated code builds with the
#       directory's flags (warnings as errors in CI): a mutation must not make a warning.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
list=${1:-$root/scripts/mutations.txt}
jobs=${JOBS:-2}
start=$SECONDS

work=$(mktemp -d)
if [ -n "${MUTATIONS_BUILD:-}" ]; then
  src=$root
  build=$(cd "$root" && cd "$MUTATIONS_BUILD" && pwd)
  # The file being mutated is kept as FILE.orig until it is restored: put back on any exit.
  trap '[ -n "${mutating:-}" ] && [ -f "$mutating.orig" ] && mv "$mutating.orig" "$mutating"; rm -rf "$work"' EXIT
else
  src=$work/src
  build=$work/build
  trap 'rm -rf "$work"' EXIT
  (cd "$root" && git ls-files -z --cached --others --exclude-standard | tar --null -T - -cf - 2>/dev/null) |
    (mkdir -p "$src" && tar -xf - -C "$src")
fi

# name|file|search|replacement|suites: regex, one mutation per line.
mapfile -t lines < <(grep -v '^[[:space:]]*\(#\|$\)' "$list")
field() { awk -F ' [|] ' -v n="$2" '{ print $n }' <<<"$1"; }
suites=()
for line in "${lines[@]}"; do
  target=$(field "$line" 5)
  read -r -a names <<<"${target%%:*}"
  suites+=("${names[@]}")
done
mapfile -t suites < <(printf '%s\n' "${suites[@]}" | sort -u)

# Every search text must occur exactly once before anything is built, so that a mutation
# whose code moved fails in seconds, not after the build and the other mutations.
# (perl: no quoting of the text.)
occurs_once() {
  SEARCH=$(field "$1" 3) perl -0777 -ne '
    my $s = $ENV{SEARCH}; my $n = () = /\Q$s\E/g; exit($n == 1 ? 0 : 1);' "$2"
}
stale=0
for line in "${lines[@]}"; do
  file=$(field "$line" 2)
  if [ ! -f "$src/$file" ] || ! occurs_once "$line" "$src/$file"; then
    echo "mutation $(field "$line" 1): the search text must occur exactly once in $file:" >&2
    echo "  $(field "$line" 3)" >&2
    stale=1
  fi
done
[ "$stale" -eq 0 ] || exit 2
[ "${MUTATIONS_CHECK_ONLY:-}" = 1 ] && { echo "mutation check: ${#lines[@]} search texts apply"; exit 0; }

echo "mutation check: ${#lines[@]} mutations; building ${suites[*]}"
if [ -z "${MUTATIONS_BUILD:-}" ]; then
  cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DRIGIDITY_BUILD_BENCHMARKS=OFF \
    -DRIGIDITY_WERROR=OFF >/dev/null
fi
cmake --build "$build" -j "$jobs" --target "${suites[@]}" >/dev/null
echo "mutation check: built in $((SECONDS - start)) s"

missed=0
for line in "${lines[@]}"; do
  t0=$SECONDS
  name=$(field "$line" 1)
  file=$(field "$line" 2)
  target=$(field "$line" 5)
  read -r -a names <<<"${target%%:*}"
  regex=$(sed 's/^ *//' <<<"${target#*:}")
  path="$src/$file"
  if [ ! -f "$path" ]; then
    echo "mutation $name: no file $file" >&2
    exit 2
  fi
  cp -p "$path" "$path.orig"
  mutating=$path
  # Replace the search text, which must occur exactly once (perl: no quoting of the text).
  if ! SEARCH=$(field "$line" 3) REPLACE=$(field "$line" 4) perl -0777 -i -pe '
      my ($s, $r) = ($ENV{SEARCH}, $ENV{REPLACE});
      my $n = () = /\Q$s\E/g;
      die "found $n times\n" unless $n == 1;
      s/\Q$s\E/$r/;' "$path"; then
    echo "mutation $name: the search text of $file must occur exactly once:" >&2
    echo "  $(field "$line" 3)" >&2
    exit 2
  fi
  if ! build_log=$(cmake --build "$build" -j "$jobs" --target "${names[@]}" 2>&1); then
    echo "$build_log" | tail -n 20 >&2
    echo "mutation $name: does not build" >&2
    exit 2
  fi
  if grep -q 'warning:' <<<"$build_log"; then
    grep 'warning:' <<<"$build_log" | head -n 5 >&2
    echo "mutation $name: builds with a warning (CI builds the mutations with warnings as errors)" >&2
    exit 2
  fi
  labels="^($(IFS='|'; echo "${names[*]}"))\$"
  set +e
  output=$(ctest --test-dir "$build" -L "$labels" -R "$regex" -j "$jobs" --timeout 120 2>&1)
  set -e
  run=$(grep -c 'Test *#' <<<"$output" || true)
  failed=$(grep -E '\*\*\*Failed|\*\*\*Timeout|\*\*\*Exception|SEGFAULT' <<<"$output" | sed -E 's/.*Test *#[0-9]+: ([^ ]+) .*/\1/' || true)
  if [ "$run" -eq 0 ]; then
    echo "mutation $name: no test matches $regex in ${names[*]}" >&2
    exit 2
  fi
  if [ -n "$failed" ]; then
    echo "mutation $name ($file): caught by $(wc -l <<<"$failed") of $run tests in $((SECONDS - t0)) s:"
    sed 's/^/    /' <<<"$failed"
  else
    echo "mutation $name ($file): NOT CAUGHT by the $run tests matching $regex"
    missed=$((missed + 1))
  fi
  mv "$path.orig" "$path"
  mutating=
  touch "$path"
done

echo "mutation check: ${#lines[@]} mutations, $missed missed, $((SECONDS - start)) s"
[ "$missed" -eq 0 ]
