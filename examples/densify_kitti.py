#!/usr/bin/env python3
"""Densify one KITTI-style frame with lidar_sgm and write the cloud and a disparity picture.

    PYTHONPATH=build/python python3 examples/densify_kitti.py --out /tmp/frame
    PYTHONPATH=build/python python3 examples/densify_kitti.py --velodyne V.bin --calib C.txt \\
        --left image_2/X.png --right image_3/X.png --out /tmp/frame --alpha 0.7

Without paths it densifies the bundled sample (data/sample). Writes OUT/cloud.ply (x, y, z, the
left image's colors and the confidence, as lidar_sgm_densify writes it: lidar_sgm.write_cloud) and
OUT/disparity.png (the disparity color-mapped, black = none; matplotlib's turbo when installed).
"""
import argparse
import pathlib
import struct
import sys
import zlib

import numpy as np

import lidar_sgm

SAMPLE = pathlib.Path(__file__).resolve().parents[1] / "data" / "sample"


def write_png(path, rgb):
    """An 8-bit RGB PNG with the standard library only (zlib)."""
    height, width, _ = rgb.shape
    rows = np.concatenate([np.zeros((height, 1), np.uint8), rgb.reshape(height, -1)], axis=1)  # filter 0

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)) + chunk(b"IEND", b""))


def color_map(disparity, max_disparity):
    """(H, W) disparity -> (H, W, 3) uint8, near (large d) warm, far cold, NaN black."""
    t = np.clip(np.nan_to_num(disparity, nan=0.0) / max_disparity, 0.0, 1.0)
    try:
        from matplotlib import colormaps
        rgb = (colormaps["turbo"](t)[..., :3] * 255.0).round().astype(np.uint8)
    except ImportError:  # a blue -> green -> red ramp
        rgb = (np.stack([np.clip(2 * t - 1, 0, 1), 1 - np.abs(2 * t - 1), np.clip(1 - 2 * t, 0, 1)], axis=-1)
               * 255.0).round().astype(np.uint8)
    rgb[~np.isfinite(disparity)] = 0
    return rgb


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--velodyne", default=str(SAMPLE / "velodyne" / "000000.bin"), help="KITTI .bin, .pcd or .ply")
    parser.add_argument("--calib", default=str(SAMPLE / "calib" / "000000.txt"), help="KITTI object/raw or YAML")
    parser.add_argument("--left", default=str(SAMPLE / "image_2" / "000000.png"))
    parser.add_argument("--right", default=str(SAMPLE / "image_3" / "000000.png"))
    parser.add_argument("--out", required=True, help="output folder (created)")
    parser.add_argument("--alpha", type=float, default=None, help="LiDAR weight of the fused cost (Eq. 5)")
    args = parser.parse_args(argv)

    points = lidar_sgm.read_cloud(args.velodyne)
    left = lidar_sgm.read_image(args.left)
    right = lidar_sgm.read_image(args.right)
    densifier = lidar_sgm.Densifier(lidar_sgm.read_calibration(args.calib), alpha=args.alpha)
    result = densifier.densify(points, left, right)
    print(f"{result.mode}: {len(points)} LiDAR points -> {len(result.points)} points, "
          f"{100 * np.isfinite(result.disparity).mean():.1f} % of pixels with a disparity, "
          f"{result.timings['total']:.0f} ms")

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    lidar_sgm.write_cloud(out / "cloud.ply", result)
    low, count = result.disparity_range
    write_png(out / "disparity.png", color_map(result.disparity, low + count))
    print(f"wrote {out / 'cloud.ply'} and {out / 'disparity.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
