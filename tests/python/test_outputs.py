"""What a DensifyResult gives besides its arrays: the per-point confidence, write_cloud (the tool's
cloud files, byte for byte), to_open3d's tensor cloud; and the errors for a wrong calibration."""
import os
import pathlib
import subprocess

import numpy as np
import pytest

import lidar_sgm
from conftest import read_pcd, sample_path


def tool_cloud(tmp_path, name, *options, images=True):
    """lidar_sgm_densify's cloud of the sample, written to tmp_path/tool/name: its bytes."""
    tool = os.environ.get("LIDAR_SGM_DENSIFY_TOOL")
    if not tool:
        pytest.skip("LIDAR_SGM_DENSIFY_TOOL is not set (ctest sets it to build/apps/lidar_sgm_densify)")
    (tmp_path / "tool").mkdir(exist_ok=True)
    out = tmp_path / "tool" / name
    command = [tool, sample_path("velodyne", "bin"), str(out), "-calib", sample_path("calib", "txt"), *options]
    if images:
        command += ["-left", sample_path("image_2"), "-right", sample_path("image_3")]
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    assert done.returncode == 0, f"{' '.join(command)}: {done.stderr}"
    return out.read_bytes()


def test_point_confidence_is_the_tools_confidence_field(tmp_path, fused):
    confidence = fused.point_confidence
    assert confidence.shape == (len(fused.points),) and confidence.dtype == np.float32
    pixels = fused.pixels
    np.testing.assert_array_equal(confidence, fused.confidence[pixels[:, 1], pixels[:, 0]].astype(np.float32) / 255.0)
    tool_cloud(tmp_path, "cloud.pcd")
    np.testing.assert_array_equal(confidence, read_pcd(str(tmp_path / "tool" / "cloud.pcd"))["confidence"])


def test_point_confidence_is_none_without_the_confidence(calibration, points, left):
    result = lidar_sgm.Densifier(calibration, no_confidence=True).densify(points, left)
    assert result.confidence is None and result.point_confidence is None


@pytest.mark.parametrize("name, format", [("cloud.pcd", "binary"), ("cloud.pcd", "compressed"),
                                          ("cloud.pcd", "ascii"), ("cloud.ply", "binary"), ("cloud.ply", "ascii")])
def test_write_cloud_writes_the_tools_file(tmp_path, fused, name, format):
    expected = tool_cloud(tmp_path, name, "-format", format)
    lidar_sgm.write_cloud(tmp_path / name, fused, format=format)
    assert (tmp_path / name).read_bytes() == expected


def test_write_cloud_without_colors_or_confidence_writes_the_tools_file(tmp_path, points):
    expected = tool_cloud(tmp_path, "cloud.pcd", "-no_confidence", "-image_size", "1242x375", images=False)
    sized = lidar_sgm.read_calibration(sample_path("calib", "txt"), 1242, 375)
    result = lidar_sgm.Densifier(sized, no_confidence=True).densify(points)
    lidar_sgm.write_cloud(str(tmp_path / "cloud.pcd"), result)
    assert (tmp_path / "cloud.pcd").read_bytes() == expected


def test_write_cloud_keeps_the_organized_grid(tmp_path, calibration, points, left):
    result = lidar_sgm.Densifier(calibration, keep_organized=True, stride=4).densify(points, left)
    lidar_sgm.write_cloud(tmp_path / "grid.pcd", result)
    header = (tmp_path / "grid.pcd").read_bytes().split(b"DATA")[0].decode()
    assert f"WIDTH {result.width}\n" in header and f"HEIGHT {result.height}\n" in header
    np.testing.assert_array_equal(read_pcd(str(tmp_path / "grid.pcd"))["x"], result.points[:, 0])


def test_write_cloud_replaces_a_file_whole_and_refuses_bad_formats(tmp_path, fused):
    out = tmp_path / "cloud.ply"
    out.write_bytes(b"old")
    with pytest.raises(ValueError, match="compressed"):
        lidar_sgm.write_cloud(out, fused, format="compressed")  # PLY has no compressed form
    with pytest.raises(ValueError, match="format"):
        lidar_sgm.write_cloud(out, fused, format="zip")
    with pytest.raises(ValueError, match=r"\.pcd"):
        lidar_sgm.write_cloud(tmp_path / "cloud.xyz", fused)
    assert out.read_bytes() == b"old"
    lidar_sgm.write_cloud(out, fused)
    assert out.read_bytes().startswith(b"ply\n")
    with pytest.raises(OSError, match="no_such_folder"):
        lidar_sgm.write_cloud(tmp_path / "no_such_folder" / "cloud.pcd", fused)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cloud.ply"]  # no temporary left


def test_to_open3d_tensor_keeps_the_confidence(fused):
    o3d = pytest.importorskip("open3d")
    cloud = lidar_sgm.to_open3d(fused, tensor=True)
    assert isinstance(cloud, o3d.t.geometry.PointCloud)
    np.testing.assert_array_equal(cloud.point.positions.numpy(), fused.points)
    np.testing.assert_array_equal(cloud.point.confidence.numpy(), fused.point_confidence.reshape(-1, 1))
    np.testing.assert_array_equal(np.round(cloud.point.colors.numpy() * 255.0).astype(np.uint8), fused.colors)


def test_to_open3d_tensor_drops_nan_points_and_their_confidence(calibration, points, left):
    pytest.importorskip("open3d")
    result = lidar_sgm.Densifier(calibration, keep_organized=True, stride=4).densify(points, left)
    finite = np.isfinite(result.points).all(axis=1)
    cloud = lidar_sgm.to_open3d(result, tensor=True)
    np.testing.assert_array_equal(cloud.point.positions.numpy(), result.points[finite])
    np.testing.assert_array_equal(cloud.point.confidence.numpy()[:, 0], result.point_confidence[finite])


def test_read_calibration_names_a_binary_file(tmp_path):
    for path in (sample_path("velodyne", "bin"), sample_path("image_2")):
        with pytest.raises(OSError) as error:
            lidar_sgm.read_calibration(path)
        assert path in str(error.value) and "looks binary" in str(error.value), str(error.value)


def test_error_messages_keep_bytes_that_are_not_utf8(tmp_path):
    path = tmp_path / "calib.txt"
    path.write_bytes(b"P0 \xff\xfe no colon here\n")
    with pytest.raises(OSError) as error:
        lidar_sgm.read_calibration(str(path))
    assert str(path) in str(error.value) and "KEY: values" in str(error.value) and "\\xff" in str(error.value)


@pytest.mark.parametrize("argument", ["data/sample/calib/000000.txt", pathlib.Path("calib.txt"), 3])
def test_densifier_says_it_wants_a_calibration(argument):
    with pytest.raises(TypeError) as error:
        lidar_sgm.Densifier(argument)
    message = str(error.value)
    assert "lidar_sgm.Calibration" in message and "lidar_sgm.read_calibration(path)" in message, message
    assert type(argument).__name__ in message, message


def test_large_outputs_lie_on_huge_pages_and_outlive_the_densifier(calibration, points, left, right):
    """The outputs of 1 MiB or more are new memory on 2 MiB-aligned huge pages every call (their
    first write would otherwise fault every 4 KiB page); each array owns its block, which stays
    valid through the next frame and the Densifier's end."""
    import gc
    densifier = lidar_sgm.Densifier(calibration)
    first = densifier.densify(points, left, right)
    arrays = {name: getattr(first, name) for name in ("disparity", "depth", "colors", "point_confidence")}
    kept = {name: np.array(array, copy=True) for name, array in arrays.items()}
    for name, array in arrays.items():
        assert array.nbytes >= 1 << 20, name  # a KITTI-size frame: each of these is a huge-page output
        assert array.ctypes.data % (2 << 20) == 0, f"{name} is not on its own huge pages"
        assert array.base is not None and array.flags.writeable and array.flags.c_contiguous, name
    second = densifier.densify(points[::2], left, right)  # other contents in the next frame's arrays
    assert not np.array_equal(second.disparity, first.disparity, equal_nan=True)
    del densifier, second, first
    gc.collect()
    for name, array in arrays.items():
        np.testing.assert_array_equal(array, kept[name], err_msg=name)
    arrays["depth"][0, 0] = 1.5  # the memory is the array's to write
    assert arrays["depth"][0, 0] == 1.5
