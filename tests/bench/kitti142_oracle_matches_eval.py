#!/usr/bin/env python3
"""The KITTI142 oracle study scores as lidar_sgm_eval scores.

    kitti142_oracle_matches_eval.py ORACLE_SCRIPT EVAL_TOOL DATA_DIR WORK_DIR

Runs bench/kitti142_point_oracle.py and `lidar_sgm_eval -protocols KITTI142` on the first two
frames and checks that the study's "every point" row (nothing left out) is the tool's fused Table
II row (error bg / fg / total, density), and that the row without both kinds of contradicted
points leaves out exactly the farther and the nearer ones the study counted per frame.
"""
import pathlib
import re
import subprocess
import sys


def main():
    oracle, tool, data, work = sys.argv[1:5]
    work = pathlib.Path(work)
    work.mkdir(parents=True, exist_ok=True)
    study = subprocess.run([sys.executable, oracle, "--data", data, "--frames", "2"], check=True,
                           capture_output=True, text=True).stdout
    rows = {m.group(1): [float(v) for v in m.group(2).split("|")]
            for m in re.finditer(r"^\| (every point|without the farther|without the nearer|without both) \|(.*)\|$",
                                 study, re.M)}
    if len(rows) != 4:
        sys.exit(f"expected the study's four rows, got {sorted(rows)}:\n{study}")
    out = work / "eval"
    subprocess.run([tool, "-backend", "cpu", "-protocols", "KITTI142", "-kitti142_frames", "2", "-alpha_step", "1",
                    "-no_pictures", "-data", str(pathlib.Path(data).parent), "-out", str(out)], check=True,
                   capture_output=True)
    section = (out / "results.md").read_text().split("## KITTI142", 1)[1].split("\n## ", 1)[0]
    fused = [line for line in section.splitlines() if line.startswith("| LiDAR-SGM (alpha 0.7) |")]
    table_ii = [float(v) for v in fused[1].strip("|").split("|")[1:5]]  # bg, fg, total, density
    if rows["every point"][1:5] != table_ii:
        sys.exit(f"the study's row {rows['every point'][1:5]} is not lidar_sgm_eval's {table_ii}")
    counts = [tuple(int(n) for n in m.groups())
              for m in re.finditer(r"^\S+: (\d+) points farther than the GT, (\d+) nearer$", study, re.M)]
    farther = sum(c[0] for c in counts)
    nearer = sum(c[1] for c in counts)
    left_out = {name: row[0] for name, row in rows.items()}
    expected = {"every point": 0, "without the farther": farther, "without the nearer": nearer,
                "without both": farther + nearer}
    if len(counts) != 2 or left_out != expected:
        sys.exit(f"points left out {left_out}, expected {expected}")
    print(f"the study's first row is lidar_sgm_eval's: {table_ii}; points left out {left_out}")


if __name__ == "__main__":
    main()
