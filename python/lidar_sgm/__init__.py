"""LiDAR-SGM: dense point clouds from a LiDAR scan and a rectified stereo pair, fused at the cost
level of Semi-Global Matching (Eq. 5 of the LiDAR-SGM paper).

    import lidar_sgm
    calib = lidar_sgm.read_calibration("data/sample/calib/000000.txt")
    points = lidar_sgm.read_kitti_bin("data/sample/velodyne/000000.bin")
    left, right = (lidar_sgm.read_image(f"data/sample/image_{i}/000000.png") for i in (2, 3))
    result = lidar_sgm.Densifier(calib, alpha=0.7).densify(points, left, right)
    cloud = lidar_sgm.to_open3d(result)  # needs open3d

The compiled module (_lidar_sgm) runs the same pipeline, with the same parameter names and
defaults, as the command-line tool lidar_sgm_densify; help(lidar_sgm.Densifier) lists them.
"""

from ._lidar_sgm import (  # noqa: F401
    Calibration,
    Densifier,
    DensifyResult,
    __version__,
    backends,
    match,
    read_calibration,
    read_cloud,
    read_image,
    read_kitti_bin,
)

__all__ = [
    "Calibration",
    "Densifier",
    "DensifyResult",
    "backends",
    "match",
    "read_calibration",
    "read_cloud",
    "read_image",
    "read_kitti_bin",
    "to_open3d",
]


def to_open3d(result):
    """An open3d.geometry.PointCloud of a DensifyResult's points (float64, as Open3D stores them)
    and, when it has them, colors (RGB in [0, 1] = colors / 255). NaN points (keep_organized) are
    left out. Imports open3d here, so that lidar_sgm itself works without it; ImportError when it
    is missing (Debian: python3-open3d).
    """
    import numpy as np
    import open3d as o3d

    points = np.asarray(result.points)
    keep = np.isfinite(points).all(axis=1)
    cloud = o3d.geometry.PointCloud()
    cloud.points = o3d.utility.Vector3dVector(points[keep].astype(np.float64))
    if result.colors is not None:
        colors = np.asarray(result.colors)[keep].astype(np.float64) / 255.0
        cloud.colors = o3d.utility.Vector3dVector(colors)
    return cloud
