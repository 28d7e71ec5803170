#!/usr/bin/env bash
# `pip install .` as a user does it, offline: copy the source (as a clone has it: git's files,
# no build directories), make a virtual environment of PYTHON with the system's site packages
# (NumPy), pip install the copy with pip's build isolation and --no-index (the build backend,
# python/build_backend/, needs nothing from an index), then import the package from another
# directory, check the paper's wall impact against its closed form, and uninstall it.
#
#   pip_install_test.sh SOURCE_DIR WORK_DIR [PYTHON]      (PYTHON: default /usr/bin/python3)
#
# 1.5 to 4.5 minutes on 2 cores (CMAKE_BUILD_PARALLEL_LEVEL, default 2): it builds the library and
# the extension afresh.
set -euo pipefail
source_dir=$(realpath "$1")
work=$2
python=${3:-/usr/bin/python3}
export CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-2}
rm -rf "$work"
mkdir -p "$work/src"
trap 'rm -rf "$work"' EXIT

if git -C "$source_dir" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  (cd "$source_dir" && git ls-files -z --cached --others --exclude-standard | tar --null -T - -cf - 2>/dev/null) |
    tar -xf - -C "$work/src"
else
  tar -C "$source_dir" --exclude='./build*' --exclude=./out --exclude=./.git -cf - . | tar -xf - -C "$work/src"
fi

"$python" -m venv --system-site-packages "$work/venv"
start=$SECONDS
if ! log=$("$work/venv/bin/python" -m pip install --no-index --no-cache-dir "$work/src" 2>&1); then
  echo "$log" | tail -n 40 >&2
  echo "pip install failed" >&2
  exit 1
fi
echo "pip install: $((SECONDS - start)) s"

cd "$work"
"$work/venv/bin/python" - "$work/venv" <<'EOF'
import os, sys
import numpy as np
import rigidity

venv = sys.argv[1]
assert rigidity.__file__.startswith(venv), rigidity.__file__
scene = {
    "name": "wall_impact",
    "materials": {"m": {"model": "rigid"}},
    "bodies": [{"name": "bar", "material": "m", "length": 1.0, "velocity": 0.6}],
    "boundaries": {"right": {"type": "wall"}},
    "time": {"end": 1.5},
    "outputs": {"probes": [{"name": "wall", "body": "bar", "at": "right", "quantities": ["p"], "every": 0.05}]},
}
t, p = rigidity.run(scene).probes["wall"]["p"]
on_wall = (t > 0) & (t < 1)
# s = sqrt((1 - v)/(1 + v)) = 0.5 and p = (1/s^2 - 1)/2 = 1.5 while the bar is on the wall.
np.testing.assert_allclose(p[on_wall], 1.5, rtol=1e-12)
print("import rigidity from %s: the wall pressure is 1.5 as the closed form says" % os.path.dirname(rigidity.__file__))
EOF

"$work/venv/bin/python" -m pip uninstall -y -q rigidity
if "$work/venv/bin/python" -c "import rigidity" 2>/dev/null; then
  echo "rigidity still imports after pip uninstall" >&2
  exit 1
fi
echo "pip install . into a virtual environment, import, uninstall: ok"
