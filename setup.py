"""The pip route: `pip install --no-build-isolation .` builds the Python module `delmesh` and the
program `delmesh` with CMake through scikit-build (classic; Debian's python3-skbuild) and installs
them into the running interpreter's environment, typically a venv made with
`/usr/bin/python3 -m venv --system-site-packages VENV` so that it sees Debian's numpy and skbuild
(nothing is fetched from PyPI; CMake finds pybind11 and the other libraries as in any build).

The build is the project's own CMake build with the tests, the experiments and the fuzzers off;
the files come from its install rules (cmake/delmesh_install.cmake, python/CMakeLists.txt):
  - the module, installed by CMake under lib/python3/dist-packages/, is delivered by build_ext as
    the distribution's extension module, so pip puts it into the environment's site-packages;
  - the program, bin/delmesh, becomes a data file under the environment's prefix (VENV/bin);
  - the libraries, headers and CMake package, which serve C++ projects (`cmake --install`, the
    Debian package), are left out.
"""

import os
import re
import shutil

from setuptools.command.build_ext import build_ext
from skbuild import setup
from skbuild.constants import CMAKE_INSTALL_DIR

# Where python/CMakeLists.txt installs the module, relative to the install prefix.
MODULE_INSTALL_DIR = "lib/python3/dist-packages"

# The module files found in CMake's install manifest, for build_ext to deliver.
module_files = []


def select_installed_files(manifest):
    """Keeps the program (bin/) as data files, sets the module aside for build_ext and drops the
    development files (libraries, headers, CMake package)."""
    kept = []
    for path in manifest:
        relative = os.path.relpath(path, CMAKE_INSTALL_DIR()).replace(os.sep, "/")
        if relative.startswith(MODULE_INSTALL_DIR + "/delmesh"):
            module_files.append(path)
        elif relative.startswith("bin/"):
            kept.append(path)
    if not module_files:
        raise SystemExit("error: the CMake build installed no Python module (is DELMESH_BUILD_PYTHON on?)")
    return kept


class BuildModule(build_ext):
    """Copies the module built by CMake to the top of the build tree (or of the source tree for
    --inplace), where setuptools expects a top-level extension module."""

    def run(self):
        destination = "." if self.inplace else self.build_lib
        os.makedirs(destination, exist_ok=True)
        for path in module_files:
            target = os.path.join(destination, os.path.basename(path))
            shutil.copyfile(path, target)
            shutil.copymode(path, target)


def project_version():
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "CMakeLists.txt")) as cmake_lists:
        match = re.search(r"project\(delmesh VERSION ([0-9.]+)", cmake_lists.read())
    return match.group(1)


setup(
    name="delmesh",
    version=project_version(),
    description="Certified meshing of smooth implicit surfaces (DelMesh)",
    license="GPL-3.0-or-later",
    python_requires=">=3.7",
    install_requires=["numpy"],
    packages=[],  # one top-level extension module, delivered by build_ext
    py_modules=[],
    cmake_languages=("CXX",),
    cmake_args=[
        "-DCMAKE_BUILD_TYPE=Release",
        "-DDELMESH_BUILD_PYTHON=ON",
        "-DDELMESH_BUILD_TESTS=OFF",
        "-DDELMESH_BUILD_EXPERIMENTS=OFF",
        "-DDELMESH_BUILD_FUZZERS=OFF",
        "-DDELMESH_SANITIZE=OFF",
    ],
    cmake_process_manifest_hook=select_installed_files,
    cmdclass={"build_ext": BuildModule},
)
