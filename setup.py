"""Builds the `ctmap` Python module with the project's CMake (target ctmap_python) for `pip install .`
(pyproject.toml says how, without downloading anything). The module is the same one the test
command builds in build/python; this only puts it where pip wants it.

CTMAP_CMAKE_BUILD_DIR: an existing CMake build tree to build the module in (the test command's
`build`, so that nothing is compiled twice); default: build/pip in the source tree."""
import os
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = os.path.abspath(os.environ.get("CTMAP_CMAKE_BUILD_DIR") or os.path.join(SOURCE, "build", "pip"))
        if not os.path.isfile(os.path.join(build, "CMakeCache.txt")):
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.check_call(["cmake", "-S", SOURCE, "-B", build, *generator, "-DCMAKE_BUILD_TYPE=Release",
                                   "-DCTMAP_BUILD_TESTS=OFF", "-DCTMAP_BUILD_BENCH=OFF",
                                   f"-DPython3_EXECUTABLE={sys.executable}"])
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 2)
        subprocess.check_call(["cmake", "--build", build, "--target", "ctmap_python", "-j", jobs])
        name = "ctmap" + sysconfig.get_config_var("EXT_SUFFIX")
        built = os.path.join(build, "python", name)
        if not os.path.isfile(built):
            sys.exit(f"setup.py: CMake built no {built} (is pybind11-dev installed? scripts/install_deps.sh)")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(ext_modules=[Extension("ctmap", sources=[])], cmdclass={"build_ext": CMakeBuild}, zip_safe=False)
