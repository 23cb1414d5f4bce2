"""Shared fixtures: the bundled sample frame (data/sample), and lidar_sgm_densify's outputs on it.

ctest (tests/CMakeLists.txt) sets PYTHONPATH to the build tree's package, LIDAR_SGM_SAMPLE_DIR and
LIDAR_SGM_DENSIFY_TOOL.
"""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import lidar_sgm

SAMPLE = pathlib.Path(os.environ.get("LIDAR_SGM_SAMPLE_DIR",
                                     pathlib.Path(__file__).resolve().parents[2] / "data" / "sample"))


def sample_path(folder, extension="png"):
    return str(SAMPLE / folder / f"000000.{extension}")


@pytest.fixture(scope="session")
def calibration():
    return lidar_sgm.read_calibration(sample_path("calib", "txt"))


@pytest.fixture(scope="session")
def points():
    return lidar_sgm.read_kitti_bin(sample_path("velodyne", "bin"))


@pytest.fixture(scope="session")
def left():
    return lidar_sgm.read_image(sample_path("image_2"))


@pytest.fixture(scope="session")
def right():
    return lidar_sgm.read_image(sample_path("image_3"))


@pytest.fixture(scope="session")
def fused(calibration, points, left, right):
    """The sample densified with the defaults, fused (left + right + LiDAR)."""
    return lidar_sgm.Densifier(calibration).densify(points, left, right)


def read_pcd(path):
    """A binary PCD as lidar_sgm_densify writes it: {field: (N,) or (N, count) array}."""
    with open(path, "rb") as f:
        header = {}
        while True:
            line = f.readline().decode("ascii").strip()
            key, _, value = line.partition(" ")
            header[key] = value.split()
            if key == "DATA":
                break
        assert header["DATA"] == ["binary"], header["DATA"]
        types = {("F", "4"): "<f4", ("F", "8"): "<f8", ("U", "1"): "u1", ("U", "4"): "<u4", ("I", "4"): "<i4"}
        dtype = np.dtype([(name, types[(t, s)], (int(c),)) if int(c) > 1 else (name, types[(t, s)])
                          for name, t, s, c in zip(header["FIELDS"], header["TYPE"], header["SIZE"], header["COUNT"])])
        count = int(header["POINTS"][0])
        records = np.frombuffer(f.read(count * dtype.itemsize), dtype=dtype, count=count)
    return {name: records[name] for name in dtype.names}


def run_tool(tmp_path, *options, images=True):
    """lidar_sgm_densify on the sample: its cloud (PCD fields) and disparity / depth PNGs."""
    tool = os.environ.get("LIDAR_SGM_DENSIFY_TOOL")
    if not tool:
        pytest.skip("LIDAR_SGM_DENSIFY_TOOL is not set (ctest sets it to build/apps/lidar_sgm_densify)")
    cloud, disparity, depth = (str(tmp_path / name) for name in ("cloud.pcd", "disparity.png", "depth.png"))
    command = [tool, sample_path("velodyne", "bin"), cloud, "-calib", sample_path("calib", "txt"),
               "-disparity", disparity, "-depth", depth, *options]
    if images:
        command += ["-left", sample_path("image_2"), "-right", sample_path("image_3")]
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert done.returncode == 0, f"{' '.join(command)}: {done.stderr}"
    return read_pcd(cloud), lidar_sgm.read_image(disparity), lidar_sgm.read_image(depth)
