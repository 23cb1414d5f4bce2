# Type stub of the package lidar_sgm (the compiled _lidar_sgm and to_open3d); parameters and
# their defaults: help(lidar_sgm.Densifier), or lidar_sgm_densify -h (the same names, without the dash).
import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Parameter = Union[int, float, str, bool, None]

class Calibration:
    """Rectified stereo rig with its LiDAR: K, baseline [m], T_cam_lidar (p_cam = T @ p_lidar), size."""
    def __init__(
        self,
        K: npt.ArrayLike,
        baseline: float,
        T_cam_lidar: Optional[npt.ArrayLike] = None,
        width: int = 0,
        height: int = 0,
    ) -> None: ...
    @property
    def K(self) -> npt.NDArray[np.float64]: ...
    @property
    def baseline(self) -> float: ...
    @property
    def T_cam_lidar(self) -> npt.NDArray[np.float64]: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def focal_baseline(self) -> float: ...
    def validate(self) -> None: ...

class DensifyResult:
    """The outputs of one frame (copies)."""
    @property
    def points(self) -> npt.NDArray[np.float32]: ...  # (M, 3)
    @property
    def colors(self) -> Optional[npt.NDArray[np.uint8]]: ...  # (M, 3) RGB, None without a left image
    @property
    def pixels(self) -> npt.NDArray[np.int32]: ...  # (M, 2) x, y
    @property
    def disparity(self) -> npt.NDArray[np.float32]: ...  # (H, W) px, NaN = none
    @property
    def depth(self) -> npt.NDArray[np.float32]: ...  # (H, W) m, 0 = none
    @property
    def confidence(self) -> Optional[npt.NDArray[np.uint8]]: ...  # (H, W) 0..255, None with no_confidence
    @property
    def point_confidence(self) -> Optional[npt.NDArray[np.float32]]: ...  # (M,) in [0, 1], None with no_confidence
    @property
    def timings(self) -> Dict[str, float]: ...  # project, match, filters (part of match), reproject, total [ms]
    @property
    def projection(self) -> Dict[str, int]: ...
    @property
    def mode(self) -> str: ...  # "fused", "lidar-only", "stereo-only"
    @property
    def backend(self) -> str: ...
    @property
    def frame(self) -> str: ...  # "lidar" or "camera"
    @property
    def disparity_range(self) -> Tuple[int, int]: ...  # (min_disparity, num_disparities)
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...

class Densifier:
    """One frame of LiDAR-SGM, as lidar_sgm_densify. Parameters (defaults as the tool's):
    alpha=0.7, alpha_mode="fixed", sigma=2.0, lidar_cost_cap=62, disparity_range="lidar",
    num_disparities=128, min_disparity=0, paths=4, p1=10, p2=100, uniqueness=0, no_lr_check=False,
    lr_check_with_lidar=False, lr_max_diff=2, median=5, census="9x7", stereo_cost_without_lidar=False,
    lidar_coverage_rows=6, no_gated_search=False, gated_search_margin=12, gated_search_rows=6, scale=1.0, threads=0, backend="auto", min_confidence=0.5,
    no_confidence=False, no_sky_filter=False, sky_texture=1.0, no_outlier_filter=False,
    outlier_min_neighbours=4, frame="lidar", max_depth=80.0, stride=1, keep_organized=False,
    no_occlusion_filter=False, no_crop_to_scan=False (help(lidar_sgm.Densifier) prints them from
    the library itself).
    """
    def __init__(self, calibration: Calibration, **parameters: _Parameter) -> None: ...
    def densify(
        self,
        points: npt.NDArray[Union[np.float32, np.float64]],
        left: Optional[npt.NDArray[Union[np.uint8, np.uint16]]] = None,
        right: Optional[npt.NDArray[Union[np.uint8, np.uint16]]] = None,
    ) -> DensifyResult: ...
    @property
    def calibration(self) -> Calibration: ...
    @property
    def parameters(self) -> Dict[str, Any]: ...

def match(
    left: Optional[npt.NDArray[Union[np.uint8, np.uint16]]],
    right: Optional[npt.NDArray[Union[np.uint8, np.uint16]]] = None,
    lidar_disparity: Optional[npt.NDArray[Union[np.float32, np.float64]]] = None,
    **parameters: _Parameter,
) -> npt.NDArray[np.float32]: ...
def read_calibration(path: str, width: int = 0, height: int = 0) -> Calibration: ...
def read_kitti_bin(path: str) -> npt.NDArray[np.float32]: ...  # (N, 4)
def read_cloud(path: str) -> npt.NDArray[np.float32]: ...  # (N, 4)
def read_image(path: str) -> npt.NDArray[Union[np.uint8, np.uint16]]: ...  # (H, W) or (H, W, 3) RGB
def backends() -> List[str]: ...
def options(cloud: bool = True) -> Dict[str, Union[bool, int, float, str]]: ...
def write_cloud(path: Union[str, os.PathLike], result: DensifyResult, format: str = "binary") -> None: ...
def to_open3d(result: DensifyResult, tensor: bool = False) -> Any: ...  # open3d.geometry.PointCloud, or open3d.t.geometry.PointCloud

# Whole sequences (mapping): a drive's frames, their calibration and poses, the merged map.
class Frame:
    @property
    def name(self) -> str: ...
    @property
    def scan(self) -> str: ...
    @property
    def left(self) -> str: ...
    @property
    def right(self) -> str: ...
    @property
    def calib(self) -> str: ...
    @property
    def velo_to_cam(self) -> str: ...
    @property
    def oxts(self) -> str: ...

def frames(path: str) -> List[Frame]: ...
def read_frame_calibration(frame: Frame, width: int = 0, height: int = 0) -> Calibration: ...
def sequence_poses(frames: List[Frame], poses: str = "") -> Tuple[List[npt.NDArray[np.float64]], str]: ...

class VoxelMap:
    def __init__(self, leaf_size: float) -> None: ...
    def add(
        self,
        points: npt.ArrayLike,
        colors: Optional[npt.ArrayLike] = None,
        confidence: Optional[npt.ArrayLike] = None,
        to_world: npt.ArrayLike = ...,
    ) -> None: ...
    def __len__(self) -> int: ...
    @property
    def leaf_size(self) -> float: ...
    @property
    def has_color(self) -> bool: ...
    @property
    def has_confidence(self) -> bool: ...
    def arrays(self) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.uint8], npt.NDArray[np.float32]]: ...
