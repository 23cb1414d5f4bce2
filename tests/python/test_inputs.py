"""Inputs: the array layouts and dtypes the module takes, and the errors for the others."""
import numpy as np
import pytest

import lidar_sgm
from conftest import sample_path


def test_strided_and_float64_inputs_give_the_same_result(calibration, points, left, right, fused):
    """Arrays in other layouts work and change nothing: rows padded (wrapped without a copy),
    every other column of a wider array (copied once), Fortran-ordered float64 points."""
    padded = np.zeros((left.shape[0], left.shape[1] + 5, 3), np.uint8)
    padded[:, 2:-3] = left
    left_view = padded[:, 2:-3]
    assert not left_view.flags.c_contiguous
    doubled = np.zeros((right.shape[0], 2 * right.shape[1], 3), np.uint8)
    doubled[:, ::2] = right
    right_view = doubled[:, ::2]
    points64 = np.asfortranarray(points[:, :3].astype(np.float64))
    result = lidar_sgm.Densifier(calibration).densify(points64, left_view, right_view)
    np.testing.assert_array_equal(result.points, fused.points)
    np.testing.assert_array_equal(result.colors, fused.colors)
    np.testing.assert_array_equal(result.disparity, fused.disparity)


def test_gray_images_match_and_color_gray(calibration, points, left, right):
    """(H, W) gray pairs are matched as they are, and color the points gray."""
    gray = [np.round(im.astype(np.float64) @ [0.299, 0.587, 0.114]).astype(np.uint8) for im in (left, right)]
    result = lidar_sgm.Densifier(calibration).densify(points, gray[0], gray[1])
    assert result.mode == "fused"
    assert np.array_equal(result.colors[:, 0], result.colors[:, 1])
    np.testing.assert_array_equal(result.colors[:, 0], gray[0][result.pixels[:, 1], result.pixels[:, 0]])


@pytest.mark.parametrize("bad, message", [
    (np.zeros((10, 2), np.float32), r"points: expected an \(N, 3\) or \(N, 4\) array of float32 or float64.*shape \(10, 2\) float32"),
    (np.zeros((10, 3), np.int32), r"points: .*shape \(10, 3\) int32"),
    (np.zeros(12, np.float32), r"points: .*shape \(12,\) float32"),
    ([[1.0, 2.0, 3.0]], r"points: .*got a list"),
])
def test_bad_points_raise_value_error(calibration, bad, message):
    with pytest.raises(ValueError, match=message):
        lidar_sgm.Densifier(calibration).densify(bad)


@pytest.mark.parametrize("bad, message", [
    (np.zeros((375, 1242), np.float32), r"left: expected an \(H, W\) gray or \(H, W, 3\) RGB array of uint8 or uint16, got shape \(375, 1242\) float32"),
    (np.zeros((375, 1242, 4), np.uint8), r"left: .*shape \(375, 1242, 4\) uint8"),
    (np.zeros((0, 5), np.uint8), r"left: .*shape \(0, 5\) uint8"),
])
def test_bad_images_raise_value_error(calibration, points, bad, message):
    with pytest.raises(ValueError, match=message):
        lidar_sgm.Densifier(calibration).densify(points, bad)


def test_mismatched_images_raise_value_error(calibration, points, left):
    with pytest.raises(ValueError, match="right needs left"):
        lidar_sgm.Densifier(calibration).densify(points, None, left)
    with pytest.raises(ValueError, match="the left image is 1242x375 but the right image is 1241x375"):
        lidar_sgm.Densifier(calibration).densify(points, left, left[:, :-1])
    with pytest.raises(ValueError, match=r"differ in bit depth \(8 vs 16 bit\)"):
        lidar_sgm.Densifier(calibration).densify(points, left, left.astype(np.uint16))
    with pytest.raises(ValueError, match="the input cloud is empty"):
        lidar_sgm.Densifier(calibration).densify(np.zeros((0, 3), np.float32), left)


@pytest.mark.parametrize("parameters, message", [
    (dict(alpha=1.5), "alpha"),
    (dict(num_disparities=100), "numDisparities"),
    (dict(census="5x5"), "option -census: '5x5' must be 9x7 or cs9x7"),
    (dict(frame="world"), "option -frame: 'world' must be lidar or camera"),
    (dict(backend="tpu"), "option -backend"),
    (dict(alphaa=0.5), r"unknown parameter 'alphaa' \(known: .*alpha,"),
    (dict(no_lr_check=1), "parameter no_lr_check: a flag, expected True or False, got 1"),
    (dict(p1=True), "parameter p1: expected a number or text, got True"),
    (dict(p1="ten"), "p1"),
])
def test_bad_parameters_raise_value_error(calibration, parameters, message):
    with pytest.raises(ValueError, match=message):
        lidar_sgm.Densifier(calibration, **parameters)


def test_parameters_are_kept(calibration):
    densifier = lidar_sgm.Densifier(calibration, alpha=0.5, no_lr_check=True, census="cs9x7", median=None)
    assert densifier.parameters == dict(alpha=0.5, no_lr_check=True, census="cs9x7", median=None)
    assert densifier.calibration.focal_baseline == pytest.approx(calibration.focal_baseline)


def test_missing_files_raise_os_error(tmp_path):
    missing = str(tmp_path / "missing")
    for read, path in [(lidar_sgm.read_kitti_bin, missing + ".bin"), (lidar_sgm.read_cloud, missing + ".pcd"),
                       (lidar_sgm.read_image, missing + ".png"), (lidar_sgm.read_calibration, missing + ".txt"),
                       (lidar_sgm.read_calibration, missing + ".yaml")]:
        with pytest.raises(OSError, match="missing"):
            read(path)
    truncated = tmp_path / "truncated.bin"
    truncated.write_bytes(b"\0" * 20)
    with pytest.raises(OSError, match="not a multiple of 16"):
        lidar_sgm.read_kitti_bin(str(truncated))
    with pytest.raises(OSError, match=r"unsupported extension .\.xyz"):
        lidar_sgm.read_cloud(str(tmp_path / "cloud.xyz"))


def test_readers(points, left, calibration):
    assert points.shape == (31598, 4) and points.dtype == np.float32
    np.testing.assert_array_equal(np.fromfile(sample_path("velodyne", "bin"), np.float32).reshape(-1, 4), points)
    assert left.shape == (375, 1242, 3) and left.dtype == np.uint8
    assert calibration.width == 0 and calibration.baseline == pytest.approx(0.54, abs=1e-6)
    assert lidar_sgm.read_calibration(sample_path("calib", "txt"), 1242, 375).width == 1242


def test_calibration_from_arrays(calibration):
    made = lidar_sgm.Calibration(K=calibration.K, baseline=calibration.baseline, T_cam_lidar=calibration.T_cam_lidar,
                                 width=1242, height=375)
    np.testing.assert_array_equal(made.K, calibration.K)
    np.testing.assert_array_equal(made.T_cam_lidar, calibration.T_cam_lidar)
    made.validate()
    with pytest.raises(ValueError, match="baseline"):
        lidar_sgm.Calibration(K=calibration.K, baseline=-0.5)
    with pytest.raises(ValueError, match=r"last row of the 4x4 transform must be \(0 0 0 1\)"):
        lidar_sgm.Calibration(K=calibration.K, baseline=0.5, T_cam_lidar=np.ones((4, 4)))
    with pytest.raises(ValueError, match="image size must be positive"):
        lidar_sgm.Calibration(K=calibration.K, baseline=0.5).validate()  # no size yet
    # A transform or an intrinsic matrix of the wrong shape is named with its shape.
    with pytest.raises(ValueError, match=r"T_cam_lidar: expected a 4x4 matrix of numbers, got shape \(3, 4\) float64"):
        lidar_sgm.Calibration(calibration.K, 0.5, calibration.T_cam_lidar[:3])
    with pytest.raises(ValueError, match=r"K: expected a 3x3 matrix of numbers, got shape \(2, 3\) float64"):
        lidar_sgm.Calibration(calibration.K[:2], 0.5)
    with pytest.raises(ValueError, match=r"K: expected a 3x3 matrix of numbers, got a str"):
        lidar_sgm.Calibration("K", 0.5)
    made = lidar_sgm.Calibration(calibration.K.tolist(), 0.5, calibration.T_cam_lidar.astype(np.float32).tolist())
    np.testing.assert_array_equal(made.K, calibration.K)


def test_match(left, right):
    lidar_png = lidar_sgm.read_image(sample_path("lidar_disp"))
    lidar = np.where(lidar_png > 0, lidar_png / 256.0, np.nan)
    stereo = lidar_sgm.match(left, right)
    fused = lidar_sgm.match(left, right, lidar_disparity=lidar.astype(np.float32))
    lidar_only = lidar_sgm.match(None, lidar_disparity=lidar)
    for disparity in (stereo, fused, lidar_only):
        assert disparity.shape == (375, 1242) and disparity.dtype == np.float32
        assert 0.3 < np.isfinite(disparity).mean() <= 1.0
    assert not np.array_equal(np.nan_to_num(stereo), np.nan_to_num(fused))
    # Ground truth: the fused disparity is the better one (the paper's point).
    gt_png = lidar_sgm.read_image(sample_path("disp_gt"))
    valid = (gt_png > 0) & np.isfinite(stereo) & np.isfinite(fused)
    gt = gt_png / 256.0
    assert np.mean(np.abs(fused - gt)[valid] > 3) < np.mean(np.abs(stereo - gt)[valid] > 3)
    with pytest.raises(ValueError, match=r"lidar_disparity: expected an \(H, W\) array of float32 or float64"):
        lidar_sgm.match(left, right, lidar_disparity=lidar_png)
    with pytest.raises(ValueError, match="lidar_disparity is 1242x375 but the images are 1241x375"):
        lidar_sgm.match(left[:, 1:], right[:, 1:], lidar_disparity=lidar)
    for nothing in (lambda: lidar_sgm.match(None), lambda: lidar_sgm.match(left),
                    lambda: lidar_sgm.match(left, lidar_disparity=np.full(left.shape[:2], np.nan))):
        with pytest.raises(ValueError, match="nothing to match: give left and right, lidar_disparity"):
            nothing()
    with pytest.raises(ValueError, match="unknown parameter 'frame'"):
        lidar_sgm.match(left, right, frame="camera")


def test_options_are_the_tools_with_their_defaults():
    cloud = lidar_sgm.options()
    assert cloud["alpha"] == pytest.approx(0.7)
    assert cloud["census"] == "9x7" and cloud["no_lr_check"] is False and cloud["max_depth"] == 80.0
    match = lidar_sgm.options(cloud=False)
    assert "frame" in cloud and "frame" not in match and set(match) < set(cloud)
