"""The module runs lidar_sgm_densify's pipeline with its defaults: the same points, colors,
disparity and depth on the bundled sample, bit for bit."""
import numpy as np
import pytest

import lidar_sgm
from conftest import run_tool, sample_path


def unpack_rgb(packed):
    """PCL's float rgb field: bytes b, g, r, a (little endian) -> (N, 3) r, g, b."""
    raw = np.ascontiguousarray(packed).view(np.uint8).reshape(-1, 4)
    return raw[:, [2, 1, 0]]


def assert_disparity_equals_png(disparity, png):
    """KITTI disparity PNG: uint16 d * 256, 0 = none (and non-positive disparities)."""
    assert disparity.shape == png.shape and disparity.dtype == np.float32
    expected = np.where(png > 0, png.astype(np.float32) / 256.0, np.nan)
    written = np.where(disparity > 0, disparity, np.nan)
    np.testing.assert_array_equal(written, expected)


def assert_depth_equals_png(depth, png):
    """KITTI depth PNG: round(m * 256), 0 = none or beyond what uint16 holds."""
    expected = np.round(depth.astype(np.float64) * 256.0)
    expected[(expected >= 65536) | (depth <= 0)] = 0
    np.testing.assert_array_equal(expected.astype(np.uint16), png)


def test_fused_equals_tool(tmp_path, fused):
    cloud, disparity_png, depth_png = run_tool(tmp_path)
    assert fused.mode == "fused" and fused.frame == "lidar"
    assert fused.points.shape == (len(cloud["x"]), 3) and fused.points.dtype == np.float32
    assert len(fused.points) > 100000
    np.testing.assert_array_equal(fused.points, np.stack([cloud["x"], cloud["y"], cloud["z"]], axis=1))
    assert fused.colors.dtype == np.uint8
    np.testing.assert_array_equal(fused.colors, unpack_rgb(cloud["rgb"]))
    np.testing.assert_array_equal(fused.confidence[fused.pixels[:, 1], fused.pixels[:, 0]].astype(np.float32) / 255.0,
                                  cloud["confidence"])
    assert_disparity_equals_png(fused.disparity, disparity_png)
    assert_depth_equals_png(fused.depth, depth_png)


def test_lidar_only_with_options_equals_tool(tmp_path, points):
    # KITTI object calibrations carry no size, and no image gives it here.
    calibration = lidar_sgm.read_calibration(sample_path("calib", "txt"), 1242, 375)
    options = dict(frame="camera", max_depth=40, no_confidence=True, alpha_mode="adaptive", p2=120)
    cloud, disparity_png, depth_png = run_tool(
        tmp_path, "-frame", "camera", "-max_depth", "40", "-no_confidence", "-alpha_mode", "adaptive", "-p2", "120",
        "-image_size", "1242x375", images=False)
    result = lidar_sgm.Densifier(calibration, **options).densify(points)
    assert result.mode == "lidar-only" and result.frame == "camera"
    assert result.colors is None and result.confidence is None
    np.testing.assert_array_equal(result.points, np.stack([cloud["x"], cloud["y"], cloud["z"]], axis=1))
    assert result.points[:, 2].max() <= 40.0
    assert_disparity_equals_png(result.disparity, disparity_png)
    assert_depth_equals_png(result.depth, depth_png)


def test_parameters_change_the_result(calibration, points, left, right, fused):
    """Keywords reach the matcher: another alpha, another disparity (the comparison with the tool's
    defaults could not tell an ignored parameter from a default one)."""
    other = lidar_sgm.Densifier(calibration, alpha=0.2).densify(points, left, right)
    assert other.mode == "fused"
    assert not np.array_equal(np.nan_to_num(other.disparity), np.nan_to_num(fused.disparity))
