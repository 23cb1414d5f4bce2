"""`pip install .`: builds the pybind11 module with CMake (the project's own build, target
_lidar_sgm only) and puts the package python/lidar_sgm with it into the wheel. Offline with what
Debian ships: `pip install --no-build-isolation .` uses the installed setuptools and wheel
(python3-setuptools, python3-wheel) instead of fetching them.

Environment:
  LIDAR_SGM_CMAKE_ARGS       more CMake arguments (shell words), e.g. "-DCMAKE_CUDA_ARCHITECTURES=75"
  LIDAR_SGM_PIP_BUILD_DIR    the CMake build folder (default: build-pip in this tree, kept between
                             installs so that the next one rebuilds only what changed)
  CMAKE_BUILD_PARALLEL_LEVEL compile jobs (default: the number of cores)
With ccache installed the compilers go through it, set up as scripts/ccache_env.sh sets up the
project's other builds: a build folder beside build/ (the same depth, so the same relative paths),
with the same options, hits what scripts/build.sh compiled.
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_DIR = os.path.abspath(os.environ.get("LIDAR_SGM_PIP_BUILD_DIR") or os.path.join(ROOT, "build-pip"))


def version():
    """project(lidar_sgm VERSION x.y.z) in CMakeLists.txt: one version for C++ and Python."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(lidar_sgm VERSION ([0-9.]+)", f.read()).group(1)


def configure_and_build(configure, build):
    """Runs the CMake commands `configure` (with scripts/ccache_env.sh's launcher arguments appended:
    none without ccache) and `build`, both in the environment that script sets (ccache reads it
    while compiling)."""
    script = ('root="$1"; shift; source "$root/scripts/ccache_env.sh"; n="$1"; shift; '
              '"${@:1:$n}" "${lidar_sgm_launcher[@]}" && "${@:$((n + 1))}"')
    subprocess.run(["bash", "-c", script, "bash", ROOT, str(len(configure)), *configure, *build], check=True)


class CMakeBuild(build_ext):
    """Builds the extension lidar_sgm._lidar_sgm with CMake instead of setuptools' compiler."""

    def build_extension(self, ext):
        build_dir = BUILD_DIR
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        configure_and_build(
            ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}",
             "-DLIDAR_SGM_BUILD_PYTHON=ON", "-DLIDAR_SGM_BUILD_TESTS=OFF",
             *shlex.split(os.environ.get("LIDAR_SGM_CMAKE_ARGS", ""))],
            ["cmake", "--build", build_dir, "--target", "_lidar_sgm", "-j", jobs])
        built = glob.glob(os.path.join(build_dir, "python", "lidar_sgm", "_lidar_sgm*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one _lidar_sgm module in {build_dir}/python/lidar_sgm, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


os.makedirs(os.path.join(BUILD_DIR, "setuptools"), exist_ok=True)  # egg_info wants its folder to exist
setup(
    version=version(),
    packages=["lidar_sgm"],
    package_dir={"": "python"},
    package_data={"lidar_sgm": ["__init__.pyi", "py.typed"]},
    ext_modules=[Extension("lidar_sgm._lidar_sgm", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own work folders inside the CMake one, not in build/ (scripts/build.sh's).
    options={"build": {"build_base": os.path.join(BUILD_DIR, "setuptools")},
             "egg_info": {"egg_base": os.path.join(BUILD_DIR, "setuptools")}},
    zip_safe=False,
)
