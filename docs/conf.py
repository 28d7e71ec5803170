# Sphinx configuration of rigidity's documentation (MyST Markdown pages).
# Built by scripts/docs.sh: sphinx-build -W --keep-going -b html docs <dir>.
# The scene reference (scene_reference.md) is generated from `rigidity schema --json`
# at build time by _ext/scene_schema.py; it finds the executable in $RIGIDITY or in
# build-tests/, build/ or build-*/ of the repository.
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "_ext"))

project = "rigidity"
author = "the rigidity authors"
copyright = "the rigidity authors"
release = "0.1.0"

extensions = ["myst_parser", "scene_schema"]
myst_enable_extensions = ["dollarmath", "deflist", "substitution"]


def _last_change(path):
    """The date git last committed `path` (a table the scripts regenerate), or 'uncommitted'."""
    import subprocess
    try:
        date = subprocess.run(["git", "log", "-1", "--format=%cs", "--", path], cwd=os.path.dirname(__file__) or ".",
                              capture_output=True, text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        date = ""
    return date or "(date unknown: not committed)"


myst_substitutions = {
    "date_second_order": _last_change("second_order.md"),
    "date_multibody_precision": _last_change("multibody_precision.md"),
    "date_work_precision": _last_change("work_precision.md"),
}
myst_heading_anchors = 3
source_suffix = {".md": "markdown"}
exclude_patterns = ["_build", "*.md.in", "second_order.md", "multibody_precision.md", "work_precision.md"]
root_doc = "index"
html_theme = "alabaster"
html_static_path = []
html_theme_options = {"fixed_sidebar": True, "page_width": "1100px"}
suppress_warnings = []

# The machine that builds the site may be offline: `-b linkcheck` checks the links
# inside the site and to files of the repository, not the web.
linkcheck_ignore = [r"https?://.*"]
