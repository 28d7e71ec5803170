"""The build backend of `pip install .` (PEP 517), in the tree and made of the standard library
alone: pip's isolated build environment has nothing to fetch, so the install works offline.
CMake builds the extension rigidity._rigidity and the library it links for the Python that runs
pip; `cmake --install --component python` of that build gives the package's files, written here
into a wheel (the library beside the extension, found through RPATH $ORIGIN).

    python3 -m pip install .                                   # from the repository's root
    python3 -m pip install . --config-settings build-dir=build-pip   # keep the build for the next install
    python3 -m pip install . --config-settings cmake-args="-DCMAKE_CXX_COMPILER=clang++"
    CMAKE_BUILD_PARALLEL_LEVEL=1 python3 -m pip install .      # compile jobs (default: all cores)

It needs what the C++ build needs (CMake, a C++20 compiler, Eigen, yaml-cpp, GSL: see
scripts/install-deps.sh) and pybind11's CMake package: Debian's python3-pybind11, or pybind11
installed into the building Python (then build with --no-build-isolation). NumPy is needed to
use the package, not to build it.
"""

import base64
import hashlib
import io
import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

NAME = "rigidity"
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _version():
    with open(os.path.join(SOURCE, "CMakeLists.txt"), encoding="utf-8") as f:
        match = re.search(r"project\(\s*rigidity\s+VERSION\s+([0-9.]+)", f.read())
    if not match:
        raise RuntimeError("rigidity: no project(rigidity VERSION ...) in %s/CMakeLists.txt" % SOURCE)
    return match.group(1)


def _metadata():
    return (
        "Metadata-Version: 2.1\n"
        "Name: %s\n"
        "Version: %s\n"
        "Summary: Relativistic continuum mechanics in one dimension: rigid bodies, shock fronts and the "
        "method of characteristics\n"
        "Requires-Python: >=3.8\n"
        "Requires-Dist: numpy\n" % (NAME, _version()))


def _dist_info():
    return "%s-%s.dist-info" % (NAME, _version())


def _tag():
    """The wheel's tag for the running interpreter: cp311-cp311-linux_x86_64 and the like."""
    version = "%d%d" % sys.version_info[:2]
    if sys.implementation.name == "cpython":
        interpreter = "cp" + version
        abi = interpreter + getattr(sys, "abiflags", "")
    else:  # PyPy: pp39-pypy39_pp73-...
        interpreter = {"pypy": "pp"}.get(sys.implementation.name, sys.implementation.name) + version
        soabi = sysconfig.get_config_var("SOABI") or "none"
        abi = "_".join(soabi.split("-")[:2]).replace(".", "_")
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return "%s-%s-%s" % (interpreter, abi, platform)


def _setting(config_settings, key):
    value = (config_settings or {}).get(key)
    if isinstance(value, list):  # given more than once
        value = " ".join(value)
    return value


def _run(command):
    print("rigidity: " + " ".join(shlex.quote(c) for c in command), flush=True)
    subprocess.run(command, check=True)


def _cmake():
    cmake = shutil.which("cmake")
    if cmake is None:
        raise RuntimeError("rigidity: `pip install` builds the extension with CMake (3.22 or later), "
                           "which is not on PATH: apt-get install cmake (scripts/install-deps.sh installs "
                           "all the build needs)")
    return cmake


def _build(build_dir, staging, config_settings):
    """Configures and builds the extension for this interpreter in build_dir, and installs the
    package's files (component python) into staging/rigidity."""
    cmake = _cmake()
    configure = [
        cmake, "-S", SOURCE, "-B", build_dir,
        "-DCMAKE_BUILD_TYPE=Release",
        "-DRIGIDITY_BUILD_TESTS=OFF", "-DRIGIDITY_BUILD_BENCHMARKS=OFF", "-DRIGIDITY_MPI=OFF",
        "-DRIGIDITY_BUILD_PYTHON=ON", "-DRIGIDITY_PYTHON_WHEEL=ON", "-DRIGIDITY_PYTHON_INSTALL_DIR=.",
        "-DPython_EXECUTABLE=" + sys.executable,
    ]
    try:  # pybind11 installed into this Python (a build without isolation); else CMake finds Debian's
        import pybind11
        configure.append("-Dpybind11_DIR=" + pybind11.get_cmake_dir())
    except ImportError:
        pass
    configure += shlex.split(_setting(config_settings, "cmake-args") or "")
    _run(configure)
    build = [cmake, "--build", build_dir, "--target", "_rigidity"]
    if not os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL"):
        build += ["--parallel", str(os.cpu_count() or 1)]
    _run(build)
    _run([cmake, "--install", build_dir, "--component", "python", "--prefix", staging])


def _package_files(staging):
    """(path in the wheel, file on disk) for the package's files. A symbolic link (the library's
    soname, librigidity.so.0 -> librigidity.so.0.1.0) is written as the file it names, under
    its own name, and that file is left out: a wheel holds no links."""
    entries, linked = [], set()
    for directory, _, names in os.walk(staging):
        for name in names:
            path = os.path.join(directory, name)
            arcname = os.path.relpath(path, staging).replace(os.sep, "/")
            if os.path.islink(path):
                linked.add(os.path.realpath(path))
                entries.append((arcname, os.path.realpath(path), True))
            else:
                entries.append((arcname, path, False))
    return sorted((arcname, path) for arcname, path, is_link in entries
                  if is_link or os.path.realpath(path) not in linked)


def _record_line(arcname, data):
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return "%s,sha256=%s,%d" % (arcname, digest, len(data))


def _write_wheel(wheel_directory, staging):
    name = "%s-%s-%s.whl" % (NAME, _version(), _tag())
    dist_info = _dist_info()
    wheel_text = ("Wheel-Version: 1.0\nGenerator: rigidity_build\nRoot-Is-Purelib: false\nTag: %s\n" % _tag())
    record = []
    path = os.path.join(wheel_directory, name)
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as wheel:
        def add(arcname, data, mode=0o644):
            info = zipfile.ZipInfo(arcname, date_time=(2020, 1, 1, 0, 0, 0))
            info.external_attr = (0o100000 | mode) << 16
            info.compress_type = zipfile.ZIP_DEFLATED
            wheel.writestr(info, data)
            record.append(_record_line(arcname, data))

        for arcname, file in _package_files(staging):
            with open(file, "rb") as f:
                data = f.read()
            add(arcname, data, 0o755 if os.access(file, os.X_OK) else 0o644)
        add(dist_info + "/METADATA", _metadata().encode())
        add(dist_info + "/WHEEL", wheel_text.encode())
        add(dist_info + "/top_level.txt", (NAME + "\n").encode())
        record.append(dist_info + "/RECORD,,")
        wheel.writestr(dist_info + "/RECORD", "\n".join(record) + "\n")
    return name


# ---- PEP 517 hooks -----------------------------------------------------------------------------

def get_requires_for_build_wheel(config_settings=None):
    return []


def get_requires_for_build_sdist(config_settings=None):
    return []


def prepare_metadata_for_build_wheel(metadata_directory, config_settings=None):
    dist_info = os.path.join(metadata_directory, _dist_info())
    os.makedirs(dist_info, exist_ok=True)
    with open(os.path.join(dist_info, "METADATA"), "w", encoding="utf-8") as f:
        f.write(_metadata())
    with open(os.path.join(dist_info, "top_level.txt"), "w", encoding="utf-8") as f:
        f.write(NAME + "\n")
    return _dist_info()


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    build_dir = _setting(config_settings, "build-dir")
    scratch = tempfile.mkdtemp(prefix="rigidity-wheel-")
    try:
        build_dir = os.path.abspath(build_dir) if build_dir else os.path.join(scratch, "build")
        staging = os.path.join(scratch, "staging")
        _build(build_dir, staging, config_settings)
        return _write_wheel(wheel_directory, staging)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)


def _source_files():
    """The files of the source distribution: git's list in a clone (tracked files and new ones
    not ignored), else the tree without build directories."""
    try:
        command = ["git", "-C", SOURCE, "ls-files", "-z", "--cached", "--others", "--exclude-standard"]
        listed = subprocess.run(command, check=True, capture_output=True).stdout
        return [f for f in listed.decode().split("\0") if f and os.path.isfile(os.path.join(SOURCE, f))]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for directory, dirs, names in os.walk(SOURCE):
            dirs[:] = [d for d in dirs
                       if not (d.startswith(("build", ".")) or d in ("out", "__pycache__"))]
            files += [os.path.relpath(os.path.join(directory, n), SOURCE) for n in names]
        return sorted(files)


def build_sdist(sdist_directory, config_settings=None):
    base = "%s-%s" % (NAME, _version())
    name = base + ".tar.gz"
    with tarfile.open(os.path.join(sdist_directory, name), "w:gz", format=tarfile.PAX_FORMAT) as sdist:
        for f in _source_files():
            sdist.add(os.path.join(SOURCE, f), arcname=base + "/" + f, recursive=False)
        info = _metadata().encode()
        member = tarfile.TarInfo(base + "/PKG-INFO")
        member.size = len(info)
        member.mode = 0o644
        sdist.addfile(member, io.BytesIO(info))
    return name
