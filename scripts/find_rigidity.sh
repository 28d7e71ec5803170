# Sourced by the scripts that run a built `rigidity`: sets RIGIDITY to $RIGIDITY if given,
# else to build-tests/rigidity or build/rigidity, whichever is built, or stops naming the
# calling script ($1) and how to build one. Run from the repository's root.
if [ -z "${RIGIDITY:-}" ]; then
  for candidate in build-tests/rigidity build/rigidity; do
    if [ -x "$candidate" ]; then RIGIDITY=$candidate; break; fi
  done
fi
if [ -z "${RIGIDITY:-}" ] || [ ! -x "$RIGIDITY" ]; then
  echo "$1: no rigidity executable (build it with scripts/test.sh or scripts/main.sh, or set RIGIDITY)" >&2
  exit 1
fi
