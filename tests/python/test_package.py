"""The package around the module: to_open3d, the type stub, the docstrings."""
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import lidar_sgm


def test_to_open3d_round_trips_points_and_colors(fused):
    o3d = pytest.importorskip("open3d")
    cloud = lidar_sgm.to_open3d(fused)
    assert isinstance(cloud, o3d.geometry.PointCloud)
    np.testing.assert_array_equal(np.asarray(cloud.points), fused.points.astype(np.float64))
    np.testing.assert_array_equal(np.round(np.asarray(cloud.colors) * 255.0).astype(np.uint8), fused.colors)


def test_to_open3d_drops_the_organized_clouds_nan_points(calibration, points, left):
    pytest.importorskip("open3d")
    result = lidar_sgm.Densifier(calibration, keep_organized=True, stride=4).densify(points, left)
    assert result.points.shape == (result.width * result.height, 3) and result.height > 1
    finite = np.isfinite(result.points).all(axis=1)
    assert 0 < finite.sum() < len(finite)
    cloud = lidar_sgm.to_open3d(result)
    np.testing.assert_array_equal(np.asarray(cloud.points), result.points[finite].astype(np.float64))


def test_imports_without_open3d():
    """open3d is imported by to_open3d only: with it unimportable, the package still works."""
    code = ("import sys; sys.modules['open3d'] = None; import lidar_sgm; print(lidar_sgm.backends());"
            "\ntry:\n  lidar_sgm.to_open3d(None)\nexcept ImportError:\n  print('ImportError')")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert "cpu_ref" in out and "ImportError" in out


def test_type_stub_names_every_public_name():
    stub = (pathlib.Path(lidar_sgm.__file__).parent / "__init__.pyi").read_text()
    assert (pathlib.Path(lidar_sgm.__file__).parent / "py.typed").exists()
    for name in lidar_sgm.__all__:
        assert f"def {name}(" in stub or f"class {name}" in stub, name


def test_docstrings_show_parameters_and_defaults():
    doc = lidar_sgm.Densifier.__doc__
    for text in ("-alpha A", "(default: 0.7)", "-num_disparities N", "-no_sky_filter", "-max_depth M", "-keep_organized"):
        assert text in doc, text
    assert "-alpha A" in lidar_sgm.match.__doc__ and "-keep_organized" not in lidar_sgm.match.__doc__
    for item in (lidar_sgm.read_kitti_bin, lidar_sgm.read_calibration, lidar_sgm.read_image, lidar_sgm.read_cloud,
                 lidar_sgm.Densifier.densify, lidar_sgm.to_open3d, lidar_sgm.Calibration):
        assert item.__doc__ and len(item.__doc__) > 40, item


def test_densify_releases_the_gil(calibration, points, left, right):
    """Another Python thread runs while a frame is densified."""
    import threading
    densifier = lidar_sgm.Densifier(calibration, threads=1)
    ticks = []
    done = threading.Event()
    worker = threading.Thread(target=lambda: (densifier.densify(points, left, right), done.set()))
    worker.start()
    while not done.is_set():
        ticks.append(1)
        done.wait(0.001)
    worker.join()
    assert len(ticks) > 20  # a frame takes >= 100 ms; with the GIL held the loop would stall


def test_readme_example_runs(monkeypatch):
    """README's "Use it from Python" block, as it is, from the repository root."""
    import re
    root = pathlib.Path(__file__).resolve().parents[2]
    readme = (root / "README.md").read_text()
    section = readme.split("## Use it from Python", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    monkeypatch.chdir(root)
    scope = {}
    exec(compile(code, "README.md", "exec"), scope)
    assert scope["result"].mode == "fused" and len(scope["result"].points) > 100000


def test_one_densifier_in_two_threads(calibration, points, left, right, fused):
    """Calls from two threads on one Densifier wait for each other: both get the frame's result."""
    from concurrent.futures import ThreadPoolExecutor
    densifier = lidar_sgm.Densifier(calibration)
    with ThreadPoolExecutor(2) as pool:
        results = list(pool.map(lambda _: densifier.densify(points, left, right), range(2)))
    for result in results:
        np.testing.assert_array_equal(result.points, fused.points)
        np.testing.assert_array_equal(result.disparity, fused.disparity)
