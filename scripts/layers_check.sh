#!/usr/bin/env bash
# Checks that no include runs from a lower layer of the tree to a higher one. The layers, lowest
# first (docs/layout.md):
#
#   core     framework/include/core, framework/src/core, materials/
#   scene    framework/include/scene, framework/src/scene
#   output   framework/include/output, framework/src/output
#   solvers  solvers/                          (headers rigidity/solvers/*)
#   sweeps   sweeps/                           (header rigidity/sweep.hpp)
#   top      cli/ (with the MPI runner cli/mpi/), python/
#
# A file of one layer may include the headers of its own layer and of the layers below it, never
# a header of a layer above: a header's include name is its path under its part's include
# directory (rigidity/sweep.hpp), or its file name for a header beside the sources
# (cli/mpi_sweep.hpp is "mpi_sweep.hpp"). Anything under rigidity/solvers/ counts as the
# solvers' even before it exists. Lists every offending include and exits 1.
set -euo pipefail
cd "$(dirname "$0")/.."

layers=(core scene output solvers sweeps top)
declare -A sources=(
  [core]="framework/include/core framework/src/core materials"
  [scene]="framework/include/scene framework/src/scene"
  [output]="framework/include/output framework/src/output"
  [solvers]="solvers"
  [sweeps]="sweeps"
  [top]="cli python"
)
# Include roots: a header's include name is its path below one of these.
declare -A roots=(
  [core]="framework/include/core"
  [scene]="framework/include/scene"
  [output]="framework/include/output"
  [solvers]="solvers/include"
  [sweeps]="sweeps/include"
  [top]="cli"
)

# The include names each layer owns, one per line.
headers_of() {
  local root
  for root in ${roots[$1]}; do
    [ -d "$root" ] && (cd "$root" && find . -name '*.hpp' -o -name '*.h' | sed 's|^\./||')
  done
  return 0
}

# check LABEL BELOW_SOLVERS FORBIDDEN ALLOWED FILES...: lists the includes of FILES that name a
# FORBIDDEN header (and not an ALLOWED one), or anything under rigidity/solvers/ when BELOW_SOLVERS.
status=0
check() {
  local label=$1 below_solvers=$2 forbidden=$3 allowed=$4
  shift 4
  [ $# -eq 0 ] && return 0
  local includes bad
  # FILE:LINE:NAME for every #include of the files.
  includes=$(grep -HnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*["<][^">]+[">]' "$@" |
             sed -E 's/^([^:]+:[0-9]+):[[:space:]]*#[[:space:]]*include[[:space:]]*["<]([^">]+)[">].*/\1:\2/' || true)
  [ -z "$includes" ] && return 0
  bad=$(awk -F: -v label="$label" -v below_solvers="$below_solvers" -v forbidden="$forbidden" -v allowed="$allowed" '
    BEGIN {
      n = split(forbidden, f, "\n"); for (k = 1; k <= n; ++k) if (f[k] != "") up[f[k]] = 1
      n = split(allowed, a, "\n"); for (k = 1; k <= n; ++k) if (a[k] != "") own[a[k]] = 1
    }
    {
      name = $3
      if (name in own) next
      if ((name in up) || (below_solvers && index(name, "rigidity/solvers/") == 1))
        printf "  %s:%s: #include \"%s\" (%s includes a higher layer)\n", $1, $2, name, label
    }' <<<"$includes")
  if [ -n "$bad" ]; then
    echo "$bad" >&2
    status=1
  fi
}

files_under() {
  local dir
  for dir in "$@"; do
    [ -d "$dir" ] && find "$dir" \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.in' \) -type f
  done | sort
}

for ((i = 0; i < ${#layers[@]} - 1; ++i)); do
  layer=${layers[$i]}
  forbidden=$(for ((j = i + 1; j < ${#layers[@]}; ++j)); do headers_of "${layers[$j]}"; done | sort -u)
  allowed=$(for ((j = 0; j <= i; ++j)); do headers_of "${layers[$j]}"; done | sort -u)
  below_solvers=0
  [[ " core scene output " == *" $layer "* ]] && below_solvers=1
  # shellcheck disable=SC2046,SC2086
  check "$layer" $below_solvers "$forbidden" "$allowed" $(files_under ${sources[$layer]})
done
# Whatever else lies under framework/ (a folder no part names yet) is framework all the same:
# it includes nothing of the solvers or above.
forbidden=$(for layer in solvers sweeps top; do headers_of $layer; done | sort -u)
allowed=$(for layer in core scene output; do headers_of $layer; done | sort -u)
# shellcheck disable=SC2046,SC2086
check framework 1 "$forbidden" "$allowed" $(comm -23 <(files_under framework) \
                                                      <(files_under ${sources[core]} ${sources[scene]} ${sources[output]}))

if [ $status -ne 0 ]; then
  echo "layers check: an include runs from a lower layer to a higher one (docs/layout.md)" >&2
  exit 1
fi
echo "layers check: no include runs from a lower layer to a higher one (${layers[*]})"
