#!/usr/bin/env python3
"""How far better LiDAR points alone could take KITTI142's Table II: an oracle study.

    PYTHONPATH=build/python python3 bench/kitti142_point_oracle.py [--data DIR] [--frames N]

For every frame of the KITTI142 set (../shared/data/kitti2015_lidar: KITTI 2015 training frames
with the raw scan of the same instant), the scan's points are projected with the frame's
calibration and held against the GT disparity (disp_occ_0) at their pixel. A point the GT
contradicts by KITTI's rule (more than 3 px and 5 %) is "farther" (the LiDAR saw past an edge,
through glass or foliage) or "nearer" (mostly a car that moved during the sweep). The fused frame
(lidar_sgm.Densifier, the tools' defaults) is then matched four times: with every point, without
the farther ones, without the nearer ones, and without both, and scored as lidar_sgm_eval scores
Table II (the wrong and the estimated pixels summed over the frames, by obj_map: background,
foreground, total; density over the GT pixels). No filter can know the GT, so the last row bounds
what any filter of the input points can reach; what stays wrong there is the matching's. Last,
the share of the background's wrong pixels that lie farther than the GT.
"""
import argparse
import pathlib
import sys

import numpy as np

import lidar_sgm

DEFAULT_DATA = pathlib.Path(__file__).resolve().parents[2] / "shared" / "data" / "kitti2015_lidar"
VARIANTS = ("every point", "without the farther", "without the nearer", "without both")


def contradicted(points, calibration, gt):
    """Per point: -1 farther than the GT at its pixel, +1 nearer, 0 agrees or no GT there."""
    height, width = gt.shape
    T = np.asarray(calibration.T_cam_lidar)
    K = np.asarray(calibration.K)
    camera = points[:, :3].astype(np.float64) @ T[:3, :3].T + T[:3, 3]
    z = camera[:, 2]
    verdict = np.zeros(len(points), np.int8)
    front = z > 0.5
    u = np.full(len(points), -1)
    v = np.full(len(points), -1)
    u[front] = np.floor(K[0, 0] * camera[front, 0] / z[front] + K[0, 2] + 0.5).astype(int)
    v[front] = np.floor(K[1, 1] * camera[front, 1] / z[front] + K[1, 2] + 0.5).astype(int)
    inside = front & (u >= 0) & (u < width) & (v >= 0) & (v < height)
    d = np.zeros(len(points))
    d[inside] = calibration.focal_baseline / z[inside]
    g = np.zeros(len(points))
    g[inside] = gt[v[inside], u[inside]]
    wrong = inside & (g > 0) & (np.abs(d - g) > 3.0) & (np.abs(d - g) > 0.05 * g)
    verdict[wrong & (d < g)] = -1
    verdict[wrong & (d > g)] = 1
    return verdict


def table_ii(disparity, gt, objects):
    """Wrong and estimated pixels by background / foreground, and the GT pixels: KITTI's D1 rule."""
    valid = gt > 0
    estimated = valid & np.isfinite(disparity)
    error = np.abs(np.where(estimated, disparity, 0.0) - gt)
    wrong = estimated & (error > 3.0) & (error > 0.05 * gt)
    foreground = objects > 0
    farther = wrong & ~foreground & (disparity < gt)
    return np.array([(wrong & ~foreground).sum(), (estimated & ~foreground).sum(), (wrong & foreground).sum(),
                     (estimated & foreground).sum(), valid.sum(), farther.sum()], np.int64)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=str(DEFAULT_DATA), help="the kitti2015_lidar folder")
    parser.add_argument("--frames", type=int, default=0, help="the first N frames only (0: every frame)")
    args = parser.parse_args(argv)
    root = pathlib.Path(args.data)
    frames = lidar_sgm.frames(str(root))
    if args.frames > 0:
        frames = frames[: args.frames]
    if not frames:
        sys.exit(f"no KITTI142 frame under {root}")
    sums = {name: np.zeros(6, np.int64) for name in VARIANTS}
    dropped = {name: 0 for name in VARIANTS}
    for frame in frames:
        left = lidar_sgm.read_image(frame.left)
        right = lidar_sgm.read_image(frame.right)
        height, width = left.shape[:2]
        calibration = lidar_sgm.read_frame_calibration(frame, width, height)
        points = lidar_sgm.read_kitti_bin(frame.scan)
        gt = lidar_sgm.read_image(str(root / "disp_occ_0" / f"{frame.name}.png")).astype(np.float64) / 256.0
        objects = lidar_sgm.read_image(str(root / "obj_map" / f"{frame.name}.png"))
        verdict = contradicted(points, calibration, gt)
        keeps = {VARIANTS[0]: np.ones(len(points), bool), VARIANTS[1]: verdict != -1, VARIANTS[2]: verdict != 1,
                 VARIANTS[3]: verdict == 0}
        densifier = lidar_sgm.Densifier(calibration, frame="camera")
        for name, keep in keeps.items():
            result = densifier.densify(points[keep], left, right)
            sums[name] += table_ii(result.disparity, gt, objects)
            dropped[name] += int((~keep).sum())
        print(f"{frame.name}: {int((verdict == -1).sum())} points farther than the GT, "
              f"{int((verdict == 1).sum())} nearer", flush=True)

    print(f"\nKITTI142 ({len(frames)} frames), fused with the tools' defaults; Table II over all pixels:\n")
    print("| input points | points left out | error bg % | error fg % | error total % | density % |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for name in VARIANTS:
        wrong_bg, estimated_bg, wrong_fg, estimated_fg, gt_pixels, _ = (int(n) for n in sums[name])
        if estimated_bg == 0 or gt_pixels == 0:
            sys.exit("nothing was estimated: check the data folder")
        fg = 100.0 * wrong_fg / estimated_fg if estimated_fg else 0.0
        total = 100.0 * (wrong_bg + wrong_fg) / (estimated_bg + estimated_fg)
        print(f"| {name} | {dropped[name]} | {100.0 * wrong_bg / estimated_bg:.2f} | {fg:.2f} | {total:.2f} | "
              f"{100.0 * (estimated_bg + estimated_fg) / gt_pixels:.2f} |")
    print("\nThe background's wrong pixels whose disparity is below the GT's (farther): " +
          ", ".join(f"{100.0 * sums[name][5] / max(sums[name][0], 1):.0f} % {name}" for name in VARIANTS))


if __name__ == "__main__":
    main()
