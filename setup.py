"""Builds skyview's Python module with CMake for setuptools (pyproject.toml; docs/python.md).

The extension skyview._skyview is CMake's target _skyview (python/CMakeLists.txt), built from the
same static library as the command line in the folder build-python/ (SKYVIEW_PYTHON_BUILD_DIR to
choose another), then copied where setuptools packs the extension.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
VERSION = re.search(r"project\(skyview VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        # One folder beside build/ (not under setuptools' own): the same depth, so ccache's
        # relative paths match a developer's build and its objects are reused.
        build = pathlib.Path(os.environ.get("SKYVIEW_PYTHON_BUILD_DIR", ROOT / "build-python")).resolve()
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 1))
        subprocess.run(
            ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DSKYVIEW_PYTHON=ON",
             "-DSKYVIEW_BUILD_TESTS=OFF", "-DSKYVIEW_BUILD_BENCH=OFF", f"-DPython_EXECUTABLE={sys.executable}"],
            check=True,
        )
        subprocess.run(["cmake", "--build", str(build), "--target", "_skyview", "-j", jobs], check=True)
        built = sorted((build / "python" / "skyview").glob("_skyview*.so"))
        if not built:
            raise RuntimeError(f"CMake built no _skyview module in {build / 'python' / 'skyview'}")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[-1], target)


setup(
    version=VERSION,
    ext_modules=[CMakeExtension("skyview._skyview")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-python/setuptools"}},
)
