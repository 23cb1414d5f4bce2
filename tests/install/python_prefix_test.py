"""The Python package installed by `cmake --install` lands where the interpreter looks.

Installs the build's component python into a temporary prefix, then asks the interpreter it was
built for (this one: ctest runs it) which site folders it searches under an installation
prefix (Debian's python3: those under /usr/local, where CMake installs by default; elsewhere: under
sys.prefix) and fails unless the package is in one of them. Then, in a neutral folder with no
PYTHONPATH, the interpreter finds no lidar_sgm; with those folders taken under the temporary
prefix instead (as site adds its own), it imports the package from there and densifies the sample.

Usage: python_prefix_test.py CMAKE BUILD_DIR CONFIG SAMPLE_DIR SHARED(ON|OFF)
"""
import json
import os
import subprocess
import sys
import sysconfig
import tempfile

SEARCHED = r"""
import json, site, sys, sysconfig
scheme = sysconfig.get_default_scheme() if hasattr(sysconfig, "get_default_scheme") else sysconfig._get_default_scheme()
prefix = "/usr/local" if scheme == "posix_local" else sys.prefix
print(json.dumps([prefix, [p for p in site.getsitepackages() if p.startswith(prefix + "/") and p in sys.path]]))
"""

IMPORT = r"""
import site, sys
prefix, local, searched, sample = sys.argv[1], sys.argv[2], sys.argv[3].split(":"), sys.argv[4]
try:
    import lidar_sgm
    sys.exit(f"FAILED: a lidar_sgm outside the prefix is importable ({lidar_sgm.__file__}): the test cannot tell")
except ImportError:
    pass
for folder in searched:  # the interpreter's own folders under `local`, taken under the prefix
    site.addsitedir(prefix + folder[len(local):])
import lidar_sgm
assert lidar_sgm._lidar_sgm.__file__.startswith(prefix + "/"), lidar_sgm._lidar_sgm.__file__
calibration = lidar_sgm.read_calibration(f"{sample}/calib/000000.txt")
points = lidar_sgm.read_kitti_bin(f"{sample}/velodyne/000000.bin")
left = lidar_sgm.read_image(f"{sample}/image_2/000000.png")
result = lidar_sgm.Densifier(calibration, stride=4).densify(points, left)
assert result.mode == "lidar-only" and len(result.points) > 1000, (result.mode, len(result.points))
print(f"lidar_sgm {lidar_sgm.__version__} from {lidar_sgm.__file__}: {len(result.points)} points")
"""


def clean_environment():
    """No PYTHONPATH or PYTHONHOME, no user site: only the interpreter's own search path."""
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "PYTHONSTARTUP")}
    env["PYTHONNOUSERSITE"] = "1"
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    cmake, build_dir, config, sample, shared = sys.argv[1:]
    with tempfile.TemporaryDirectory(prefix="lidar_sgm_python_prefix.") as work:
        prefix = os.path.join(work, "prefix")
        # A shared build's module needs the libraries too (the default component).
        components = ["python"] + (["Unspecified"] if shared == "ON" else [])
        for component in components:
            subprocess.run([cmake, "--install", build_dir, "--prefix", prefix, "--config", config,
                            "--component", component], check=True, stdout=subprocess.DEVNULL)
        found = [os.path.relpath(root, prefix) for root, _, files in os.walk(prefix)
                 if os.path.basename(root) == "lidar_sgm" and "__init__.py" in files]
        if len(found) != 1:
            sys.exit(f"FAILED: expected one installed package lidar_sgm under {prefix}, found {found}")
        installed = os.path.dirname(found[0])
        print(f"installed: PREFIX/{installed}/lidar_sgm")

        neutral = os.path.join(work, "neutral")
        os.mkdir(neutral)
        env = clean_environment()
        local, searched = json.loads(subprocess.run(
            [sys.executable, "-c", SEARCHED], cwd=neutral, env=env, check=True, capture_output=True, text=True).stdout)
        relative = [os.path.relpath(folder, local) for folder in searched]
        print(f"{sys.executable} ({sysconfig.get_python_version()}) searches under {local}: {relative}")
        if installed not in relative:
            sys.exit(f"FAILED: the package is installed to PREFIX/{installed}, which {sys.executable} does not "
                     f"search under an installation prefix ({local}: {', '.join(relative) or 'nothing'})")

        done = subprocess.run([sys.executable, "-c", IMPORT, prefix, local, ":".join(searched), sample],
                              cwd=neutral, env=env)
        if done.returncode != 0:
            sys.exit("FAILED: the installed package does not import and densify (above)")
    print("python prefix test: passed")


if __name__ == "__main__":
    main()
