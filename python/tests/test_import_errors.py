"""`import rigidity` where it cannot work says why and what to install: NumPy missing, the
compiled module missing (the source's python/rigidity), or built for another Python."""

import os
import shutil
import subprocess
import sys

import rigidity

PACKAGE = os.path.dirname(os.path.abspath(rigidity.__file__))


def import_error(path, prelude=""):
    """The last line of what `import rigidity` prints with `path` first on sys.path."""
    code = "import sys\nsys.path.insert(0, %r)\n%s\nimport rigidity" % (path, prelude)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=path)
    assert done.returncode != 0, done.stdout
    return done.stderr.strip().splitlines()[-1]


def package_copy(tmp_path, *extensions):
    os.makedirs(tmp_path / "rigidity")
    shutil.copy(os.path.join(PACKAGE, "__init__.py"), tmp_path / "rigidity")
    for name in extensions:
        (tmp_path / "rigidity" / name).write_bytes(b"")
    return str(tmp_path)


def test_without_numpy_it_says_to_install_numpy_into_this_interpreter():
    # sys.modules["numpy"] = None makes `import numpy` fail as it does where NumPy is not installed.
    message = import_error(os.path.dirname(PACKAGE), 'sys.modules["numpy"] = None')
    assert message.startswith("ImportError: rigidity needs NumPy")
    assert "%s -m pip install numpy" % sys.executable in message
    assert "python3-numpy" in message


def test_without_the_compiled_module_it_says_how_to_build_it(tmp_path):
    message = import_error(package_copy(tmp_path))
    assert "compiled module _rigidity is not in" in message
    assert "%s -m pip install ." % sys.executable in message


def test_a_module_built_for_another_python_is_named_as_such(tmp_path):
    message = import_error(package_copy(tmp_path, "_rigidity.cpython-29-x86_64-linux-gnu.so"))
    assert "_rigidity.cpython-29-x86_64-linux-gnu.so) was built for another Python" in message
    assert "%s -m pip install ." % sys.executable in message
