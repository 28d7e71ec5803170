#!/usr/bin/env bash
# Executes every Jupyter notebook in examples/ (nbclient and ipykernel, Debian's
# python3-nbclient and python3-ipykernel) and fails on the first cell that raises; the
# notebooks check their runs against closed forms with assertions. The kernel is $PYTHON
# (default Debian's /usr/bin/python3); if it cannot import rigidity, the package of the build
# tree is used (build-tests/python, from scripts/test.sh). The executed notebooks, figures
# included, are written to build-notebooks/. A few seconds a notebook.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
python=${PYTHON:-/usr/bin/python3}
export PYDEVD_DISABLE_FILE_VALIDATION=1   # ipykernel's debugger warns of frozen modules otherwise

if ! "$python" -c "import rigidity" 2>/dev/null; then
  for candidate in build-tests/python build/python; do
    if compgen -G "$candidate/rigidity/_rigidity*.so" >/dev/null; then
      export PYTHONPATH=$(realpath "$candidate")${PYTHONPATH:+:$PYTHONPATH}
      break
    fi
  done
fi
if ! error=$("$python" -c "import rigidity" 2>&1); then
  echo "notebooks: $python cannot import rigidity: build it (bash scripts/test.sh) or install it" >&2
  echo "(docs/python.md); the import said:" >&2
  echo "$error" | tail -n 1 >&2
  exit 1
fi

mkdir -p build-notebooks
"$python" - build-notebooks examples/*.ipynb <<'PYTHON'
import json
import os
import re
import shutil
import sys
import tempfile
import time

import nbclient
import nbformat

out, notebooks = sys.argv[1], sys.argv[2:]
# A kernel of this interpreter (Debian's kernel.json names /usr/bin/python3 whoever asks).
kernels = tempfile.mkdtemp(prefix="rigidity-kernels-")
os.makedirs(os.path.join(kernels, "kernels", "rigidity-python"))
with open(os.path.join(kernels, "kernels", "rigidity-python", "kernel.json"), "w") as f:
    json.dump({"argv": [sys.executable, "-m", "ipykernel_launcher", "-f", "{connection_file}"],
               "display_name": "Python 3", "language": "python"}, f)
os.environ["JUPYTER_PATH"] = kernels + os.pathsep + os.environ.get("JUPYTER_PATH", "")
try:
    for path in notebooks:
        start = time.monotonic()
        notebook = nbformat.read(path, as_version=4)
        # The kernel runs in the notebook's directory (scene paths are relative to it).
        client = nbclient.NotebookClient(notebook, timeout=300, kernel_name="rigidity-python",
                                         resources={"metadata": {"path": os.path.dirname(path)}})
        try:
            client.execute()
        except nbclient.exceptions.CellExecutionError as error:
            # The traceback without IPython's terminal colours.
            print("notebooks: %s failed:\n%s" % (path, re.sub(r"\x1b\[[0-9;]*m", "", str(error))), file=sys.stderr)
            sys.exit(1)
        finally:
            nbformat.write(notebook, os.path.join(out, os.path.basename(path)))
        print("notebooks: %s ran in %.1f s (executed copy in %s/)" % (path, time.monotonic() - start, out))
finally:
    shutil.rmtree(kernels)
PYTHON
