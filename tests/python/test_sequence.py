"""Whole sequences from Python: the frames of a layout, their calibration and poses, and the voxel
map, as lidar_sgm_batch reads and merges them."""
import numpy as np
import pytest

import lidar_sgm
from conftest import SAMPLE, sample_path


def test_frames_of_a_kitti_object_layout_and_their_calibration(calibration):
    frames = lidar_sgm.frames(str(SAMPLE))
    assert [f.name for f in frames] == ["000000"]
    frame = frames[0]
    assert frame.scan == sample_path("velodyne", "bin")
    assert frame.left == sample_path("image_2") and frame.right == sample_path("image_3")
    assert frame.oxts == ""
    read = lidar_sgm.read_frame_calibration(frame)
    np.testing.assert_array_equal(read.K, calibration.K)
    np.testing.assert_array_equal(read.T_cam_lidar, calibration.T_cam_lidar)
    with pytest.raises(ValueError, match="KITTI"):
        lidar_sgm.frames(str(SAMPLE / "velodyne"))  # no layout


def test_frames_of_a_list_file(tmp_path):
    listing = tmp_path / "frames.txt"
    listing.write_text(f"{sample_path('velodyne', 'bin')} - - {sample_path('calib', 'txt')}\n")
    frames = lidar_sgm.frames(str(listing))
    assert len(frames) == 1 and frames[0].left == "" and frames[0].right == ""


# KITTI raw's calibration pair (the 2011_09_26 numbers), as KITTI stereo 2015 gives it per frame.
CAM_TO_CAM = ("S_rect_02: 1.242000e+03 3.750000e+02\nR_rect_00: 1 0 0 0 1 0 0 0 1\n"
              "P_rect_02: 721.5377 0 609.5593 44.85728 0 721.5377 172.854 0.2163791 0 0 1 0.002745884\n"
              "P_rect_03: 721.5377 0 609.5593 -339.5242 0 721.5377 172.854 2.199936 0 0 1 0.002729905\n")
VELO_TO_CAM = "R: 0 -1 0 0 0 -1 1 0 0\nT: 0 -0.08 -0.27\n"


def test_frames_of_kitti_stereo_2015_are_its_scanned_frames(tmp_path):
    for name in ("000007_10", "000007_11", "000012_10", "000012_11"):
        for folder in ("image_2", "image_3"):
            (tmp_path / folder).mkdir(exist_ok=True)
            (tmp_path / folder / f"{name}.png").touch()
    (tmp_path / "velodyne").mkdir()
    (tmp_path / "velodyne" / "000007_10.bin").touch()  # 000012_10 has no scan: no frame
    for folder, text in (("calib_cam_to_cam", CAM_TO_CAM), ("calib_velo_to_cam", VELO_TO_CAM)):
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "000007.txt").write_text(text)
    frames = lidar_sgm.frames(str(tmp_path))
    assert [f.name for f in frames] == ["000007_10"]
    frame = frames[0]
    assert frame.left == str(tmp_path / "image_2" / "000007_10.png")
    assert frame.right == str(tmp_path / "image_3" / "000007_10.png")
    assert frame.calib == str(tmp_path / "calib_cam_to_cam" / "000007.txt")
    assert frame.velo_to_cam == str(tmp_path / "calib_velo_to_cam" / "000007.txt")
    read = lidar_sgm.read_frame_calibration(frame)
    assert read.baseline == pytest.approx(384.38147 / 721.5377)
    assert (read.width, read.height) == (1242, 375)
    (tmp_path / "calib_velo_to_cam" / "000007.txt").unlink()
    (tmp_path / "calib_velo_to_cam").rmdir()
    with pytest.raises(ValueError, match="calib_velo_to_cam/"):
        lidar_sgm.frames(str(tmp_path))  # half of KITTI 2015's calibration


def test_sequence_poses_from_a_poses_file(tmp_path):
    frames = lidar_sgm.frames(str(SAMPLE))
    poses_file = tmp_path / "poses.txt"
    poses_file.write_text("1 0 0 0.5 0 1 0 -2 0 0 1 3\n")
    poses, source = lidar_sgm.sequence_poses(frames, str(poses_file))
    assert str(poses_file) in source
    expected = np.eye(4)
    expected[:3, 3] = (0.5, -2, 3)
    np.testing.assert_array_equal(poses[0], expected)
    with pytest.raises(ValueError):
        lidar_sgm.sequence_poses(frames)  # an object layout has no poses of its own


def test_voxel_map_keeps_one_mean_point_per_voxel():
    voxel_map = lidar_sgm.VoxelMap(1.0)
    points = np.array([[0.1, 0.1, 0.1], [0.3, 0.5, 0.7], [5.5, 0.5, 0.5], [np.nan, 0, 0]], dtype=np.float32)
    colors = np.array([[10, 20, 30], [30, 40, 50], [255, 0, 0], [0, 0, 0]], dtype=np.uint8)
    to_world = np.eye(4)
    to_world[0, 3] = 10.0
    voxel_map.add(points, colors=colors, to_world=to_world)
    assert len(voxel_map) == 2 and voxel_map.has_color and not voxel_map.has_confidence
    xyz, rgb, confidence = voxel_map.arrays()
    np.testing.assert_allclose(xyz[0], (10.2, 0.3, 0.4), rtol=1e-6)
    np.testing.assert_array_equal(rgb[0], (20, 30, 40))
    np.testing.assert_array_equal(xyz[1], (15.5, 0.5, 0.5))
    np.testing.assert_array_equal(confidence, (0, 0))
    with pytest.raises(ValueError, match=r"colors: expected an \(N, 3\) array"):
        voxel_map.add(points, colors=colors[:2])
    with pytest.raises(ValueError):
        lidar_sgm.VoxelMap(0.0)
