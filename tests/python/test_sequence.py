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
