"""`pip install --no-build-isolation .`: the verifybench Python package, built by the project's CMake.

The metadata is in pyproject.toml; the version is the CMake project's. Offline with Debian's
python3-setuptools, python3-wheel and python3-pip (no PEP 517 backend that drives CMake is packaged
in Debian 12). The compiled extension comes from a CMake configure, a build of the
verifybench_python target only, and `cmake --install --component python` into a staging folder, so
the package holds exactly what `cmake --install` installs (the module, __init__.py with
load_report, the .pyi stubs, py.typed).

Environment:
  VERIFYBENCH_BUILD_DIR   the CMake build tree (default build-pip/cmake, kept between runs for
                          incremental rebuilds); an already configured tree (e.g. build) is reused
                          as it is, only its verifybench_python target is built
  VERIFYBENCH_CMAKE_ARGS  more configure arguments for a new tree (e.g. -DVERIFYBENCH_WITH_OPEN3D=OFF)
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: every CPU)
"""
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
WORK = "build-pip"  # setuptools' build and egg-info folders (ignored by git as /build*/)


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        match = re.search(r"project\(\s*verifybench\s+VERSION\s+([0-9][0-9.]*)", f.read())
    if not match:
        raise RuntimeError("CMakeLists.txt: no project(verifybench VERSION ...)")
    return match.group(1)


class CMakeBuild(build_ext):
    def run(self):
        for ext in self.extensions:
            self.build_extension(ext)

    def build_extension(self, ext):
        build_dir = os.path.abspath(os.environ.get("VERIFYBENCH_BUILD_DIR")
                                    or os.path.join(ROOT, WORK, "cmake"))
        if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            self.spawn(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                        "-DPYTHON_EXECUTABLE=" + sys.executable, "-DVERIFYBENCH_WITH_PYTHON=ON",
                        "-DVERIFYBENCH_BUILD_TESTS=OFF", "-DVERIFYBENCH_BUILD_BENCHMARKS=OFF"]
                       + shlex.split(os.environ.get("VERIFYBENCH_CMAKE_ARGS", "")))
        build = ["cmake", "--build", build_dir, "--target", "verifybench_python"]
        if "CMAKE_BUILD_PARALLEL_LEVEL" not in os.environ:
            build += ["--parallel", str(os.cpu_count() or 1)]
        self.spawn(build)

        stage = os.path.join(os.path.abspath(self.build_temp), "stage")
        shutil.rmtree(stage, ignore_errors=True)
        self.spawn(["cmake", "--install", build_dir, "--component", "python", "--prefix", stage])
        package = next((d for d, _, files in os.walk(stage)
                        if os.path.basename(d) == "verifybench" and "__init__.py" in files), None)
        if package is None:
            raise RuntimeError(f"{build_dir}: `cmake --install --component python` installed no "
                               "verifybench package (pybind11-dev and python3-dev installed?)")
        target = self.get_ext_fullpath(ext.name)
        module = os.path.join(package, os.path.basename(target))
        if not os.path.exists(module):
            raise RuntimeError(f"{build_dir}: no {os.path.basename(target)} (the tree was "
                               f"configured for another Python than {sys.executable}?); "
                               f"found {sorted(os.listdir(package))}")
        os.makedirs(os.path.dirname(target), exist_ok=True)
        for name in os.listdir(package):
            if self.inplace and os.path.join(package, name) != module:
                continue  # in place: the sources are already there
            shutil.copy2(os.path.join(package, name), os.path.join(os.path.dirname(target), name))


setup(
    version=project_version(),
    packages=[],  # the package comes whole from CMake (build_ext); no discovery in this tree
    ext_modules=[Extension("verifybench._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
    options={"build": {"build_base": WORK}, "egg_info": {"egg_base": WORK}},
)
