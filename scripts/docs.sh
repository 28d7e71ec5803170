#!/usr/bin/env bash
# Builds the documentation site (docs/, Sphinx with MyST Markdown) into build-docs/html.
# Every warning is an error, a broken reference between pages included; then the links
# to pages, anchors-free files and figures are checked (linkcheck, offline: links to the
# web are not followed). The scene reference is generated from `rigidity schema`: the
# executable is $RIGIDITY, else build-tests/rigidity or build/rigidity (build it first
# with scripts/test.sh or scripts/main.sh). The tutorial's scene files are validated
# with it. Under a minute.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh

source scripts/find_rigidity.sh docs
export RIGIDITY=$(realpath "$RIGIDITY")

for scene in examples/tutorial/*.yaml; do
  "$RIGIDITY" validate "$scene" >/dev/null
done

out=build-docs
rm -rf "$out"
sphinx-build -q -W --keep-going -b html docs "$out/html"
sphinx-build -q -W --keep-going -b linkcheck docs "$out/linkcheck"
echo "docs: $out/html/index.html"
