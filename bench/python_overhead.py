#!/usr/bin/env python3
"""What the Python module adds to a frame: Densifier.densify's wall time against the C++
Densifier::run inside the same call (its own timings: project + match + reproject), paired per
call. The difference is everything the binding does: reading the points array, wrapping the
images, the gray conversion and copies the C++ tool does too (setStereoPair, setColorImage), and
copying the outputs into numpy arrays. Prints the median of the runs and the overhead in ms and %,
and first the warm-up call's times: the first frame of the process, which pays the first touch of
every buffer (run it in fresh processes to compare that).

    PYTHONPATH=build/python python3 bench/python_overhead.py [--runs 20] [--frame DIR NAME]
"""
import argparse
import pathlib
import statistics
import time

import lidar_sgm

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20)
    parser.add_argument("--frame", nargs=2, metavar=("DIR", "NAME"), default=[str(ROOT / "data" / "sample"), "000000"],
                        help="a KITTI object layout (velodyne/, calib/, image_2/, image_3/) and the frame's name")
    args = parser.parse_args()
    folder, name = pathlib.Path(args.frame[0]), args.frame[1]
    points = lidar_sgm.read_kitti_bin(str(folder / "velodyne" / f"{name}.bin"))
    left = lidar_sgm.read_image(str(folder / "image_2" / f"{name}.png"))
    right = lidar_sgm.read_image(str(folder / "image_3" / f"{name}.png"))
    densifier = lidar_sgm.Densifier(lidar_sgm.read_calibration(str(folder / "calib" / f"{name}.txt")))
    start = time.perf_counter()
    first = densifier.densify(points, left, right)  # warm-up: the matcher and its buffers
    print(f"first call: densify() {1000.0 * (time.perf_counter() - start):.1f} ms, "
          f"Densifier::run {first.timings['total']:.1f} ms")
    walls, cores = [], []
    for _ in range(args.runs):
        start = time.perf_counter()
        result = densifier.densify(points, left, right)
        walls.append(1000.0 * (time.perf_counter() - start))
        cores.append(result.timings["total"])
    overheads = [w - c for w, c in zip(walls, cores)]
    wall, core, overhead = statistics.median(walls), statistics.median(cores), statistics.median(overheads)
    print(f"{name}: {left.shape[1]}x{left.shape[0]}, {len(points)} LiDAR points -> {len(result.points)} points, "
          f"{result.mode}, backend {result.backend}, {args.runs} runs")
    print(f"median densify() {wall:.1f} ms, Densifier::run {core:.1f} ms, overhead {overhead:.2f} ms "
          f"({100.0 * overhead / core:.1f} %; per-run overhead {min(overheads):.2f}-{max(overheads):.2f} ms)")


if __name__ == "__main__":
    main()
