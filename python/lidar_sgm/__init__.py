"""LiDAR-SGM: dense point clouds from a LiDAR scan and a rectified stereo pair, fused at the cost
level of Semi-Global Matching (Eq. 5 of the LiDAR-SGM paper).

    import lidar_sgm
    calib = lidar_sgm.read_calibration("data/sample/calib/000000.txt")
    points = lidar_sgm.read_kitti_bin("data/sample/velodyne/000000.bin")
    left, right = (lidar_sgm.read_image(f"data/sample/image_{i}/000000.png") for i in (2, 3))
    result = lidar_sgm.Densifier(calib, alpha=0.7).densify(points, left, right)
    lidar_sgm.write_cloud("dense.pcd", result)  # as lidar_sgm_densify writes its cloud
    cloud = lidar_sgm.to_open3d(result, tensor=True)  # needs open3d; keeps the confidence

The compiled module (_lidar_sgm) runs the same pipeline, with the same parameter names and
defaults, as the command-line tool lidar_sgm_densify; help(lidar_sgm.Densifier) lists them.
"""

from ._lidar_sgm import (  # noqa: F401
    Calibration,
    Densifier,
    DensifyResult,
    Frame,
    VoxelMap,
    __version__,
    backends,
    options,
    frames,
    match,
    read_calibration,
    read_cloud,
    read_frame_calibration,
    read_image,
    read_kitti_bin,
    sequence_poses,
    write_cloud,
)

__all__ = [
    "Calibration",
    "Densifier",
    "DensifyResult",
    "Frame",
    "VoxelMap",
    "backends",
    "options",
    "frames",
    "match",
    "read_calibration",
    "read_cloud",
    "read_frame_calibration",
    "read_image",
    "read_kitti_bin",
    "sequence_poses",
    "to_open3d",
    "write_cloud",
]


def to_open3d(result, tensor=False):
    """The DensifyResult's cloud for Open3D, without its NaN points (keep_organized). Imports open3d
    here, so that lidar_sgm itself works without it; ImportError when it is missing (Debian:
    python3-open3d).

    tensor=True: an open3d.t.geometry.PointCloud with the point attributes `positions` (N, 3)
    float32, `colors` (N, 3) float32 in [0, 1] (colors / 255) when the result has colors, and
    `confidence` (N, 1) float32 in [0, 1] (result.point_confidence) unless no_confidence: the
    fields, and the attribute names, of lidar_sgm_densify's cloud as open3d.t.io.read_point_cloud
    reads it.

    tensor=False (the default): a legacy open3d.geometry.PointCloud, points float64 and colors as
    above. A legacy cloud has no place for a per-point value: its confidence, aligned with its
    points, is result.point_confidence[numpy.isfinite(result.points).all(axis=1)].
    """
    import numpy as np
    import open3d as o3d

    points = np.asarray(result.points)
    keep = np.isfinite(points).all(axis=1)
    colors = None if result.colors is None else np.asarray(result.colors)[keep].astype(np.float32) / np.float32(255.0)
    if tensor:
        cloud = o3d.t.geometry.PointCloud(o3d.core.Tensor(np.ascontiguousarray(points[keep], dtype=np.float32)))
        if colors is not None:
            cloud.point.colors = o3d.core.Tensor(colors)
        if result.point_confidence is not None:
            confidence = np.asarray(result.point_confidence, dtype=np.float32)[keep].reshape(-1, 1)
            cloud.point.confidence = o3d.core.Tensor(confidence)
        return cloud
    cloud = o3d.geometry.PointCloud()
    cloud.points = o3d.utility.Vector3dVector(points[keep].astype(np.float64))
    if colors is not None:
        cloud.colors = o3d.utility.Vector3dVector(colors.astype(np.float64))
    return cloud
