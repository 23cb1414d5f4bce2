#!/usr/bin/env python3
"""Writes the fuzz targets' seed corpora from the bundled sample (data/sample) into OUT/<target>/:
a few small, valid files of each format. Usage: make_seeds.py OUT"""
import os
import struct
import sys
import zlib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SAMPLE = os.path.join(ROOT, "data", "sample")
POINTS = 24  # a seed is small: libFuzzer mutates it thousands of times a second


def write(out, target, name, data):
    os.makedirs(os.path.join(out, target), exist_ok=True)
    with open(os.path.join(out, target, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def lzf_literals(data):
    """LZF with literal runs only (control byte n-1, then n <= 32 bytes): valid, if not small."""
    out = bytearray()
    for i in range(0, len(data), 32):
        chunk = data[i:i + 32]
        out.append(len(chunk) - 1)
        out += chunk
    return bytes(out)


def pcd_header(fields, sizes, types, width, height, data):
    return ("# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS %s\nSIZE %s\nTYPE %s\nCOUNT %s\n"
            "WIDTH %d\nHEIGHT %d\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS %d\nDATA %s\n" %
            (" ".join(fields), " ".join(map(str, sizes)), " ".join(types), " ".join("1" * len(fields)),
             width, height, width * height, data)).encode()


def png(width, height, depth, rows):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\0" + row for row in rows)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, depth, 0, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def main(out):
    with open(os.path.join(SAMPLE, "velodyne", "000000.bin"), "rb") as f:
        scan = f.read(16 * POINTS)
    points = [struct.unpack("<4f", scan[16 * i:16 * i + 16]) for i in range(POINTS)]
    write(out, "fuzz_kitti_bin", "scan.bin", scan)

    xyzi = b"".join(struct.pack("<4f", *p) for p in points)
    fields, sizes, types = ["x", "y", "z", "intensity"], [4, 4, 4, 4], ["F", "F", "F", "F"]
    ascii_body = "".join("%.9g %.9g %.9g %.9g\n" % p for p in points)
    write(out, "fuzz_pcd", "ascii.pcd", pcd_header(fields, sizes, types, POINTS, 1, "ascii") + ascii_body.encode())
    write(out, "fuzz_pcd", "binary.pcd", pcd_header(fields, sizes, types, 6, 4, "binary") + xyzi)
    columns = b"".join(b"".join(struct.pack("<f", p[k]) for p in points) for k in range(4))
    block = lzf_literals(columns)
    write(out, "fuzz_pcd", "compressed.pcd", pcd_header(fields, sizes, types, POINTS, 1, "binary_compressed") +
          struct.pack("<II", len(block), len(columns)) + block)
    xyzd = b"".join(struct.pack("<3dB", p[0], p[1], p[2], int(p[3] * 255)) for p in points)
    write(out, "fuzz_pcd", "double.pcd", pcd_header(["x", "y", "z", "intensity"], [8, 8, 8, 1], ["F", "F", "F", "U"],
                                                    POINTS, 1, "binary") + xyzd)

    ply = "ply\nformat %s 1.0\ncomment seed\nelement vertex %d\nproperty float x\nproperty float y\n" \
          "property float z\nproperty float intensity\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"
    write(out, "fuzz_ply", "ascii.ply", (ply % ("ascii", POINTS)).encode() + ascii_body.encode())
    write(out, "fuzz_ply", "little.ply", (ply % ("binary_little_endian", POINTS)).encode() + xyzi)
    write(out, "fuzz_ply", "big.ply", (ply % ("binary_big_endian", POINTS)).encode() +
          b"".join(struct.pack(">4f", *p) for p in points))
    grid = ("ply\nformat ascii 1.0\nobj_info num_cols 3\nobj_info num_rows 2\nelement vertex 5\nproperty float x\n"
            "property float y\nproperty float z\nelement range_grid 6\nproperty list uchar int vertex_indices\n"
            "end_header\n" + "".join("%.9g %.9g %.9g\n" % p[:3] for p in points[:5]) + "1 0\n1 1\n0\n1 2\n1 3\n1 4\n")
    write(out, "fuzz_ply", "organized.ply", grid)

    with open(os.path.join(SAMPLE, "calib", "000000.txt")) as f:
        calib = f.read()
    write(out, "fuzz_kitti_calib", "000000.txt", calib)
    keys = dict((line.split(":")[0], line.split(":", 1)[1].strip()) for line in calib.splitlines() if ":" in line)
    tr = keys["Tr_velo_to_cam"].split()
    cam = "calib_time: 09-Jan-2012 13:57:47\nS_rect_02: 1.242000e+03 3.750000e+02\nR_rect_00: %s\nP_rect_02: %s\n" \
          "P_rect_03: %s\n" % (keys["R0_rect"], keys["P2"], keys["P3"])
    velo = "calib_time: 15-Mar-2012 11:37:16\nR: %s\nT: %s\n" % (" ".join(tr[0:3] + tr[4:7] + tr[8:11]),
                                                                   " ".join([tr[3], tr[7], tr[11]]))
    write(out, "fuzz_kitti_raw_calib", "raw.txt", cam + "\0" + velo)

    p2 = [float(v) for v in keys["P2"].split()]
    p3 = [float(v) for v in keys["P3"].split()]
    K = [p2[0], 0, p2[2], 0, p2[5], p2[6], 0, 0, 1]
    T = [float(v) for v in tr] + [0, 0, 0, 1]
    matrix = lambda n, v: "!!opencv-matrix\n   rows: %d\n   cols: %d\n   dt: d\n   data: [ %s ]\n" % (
        n, n, ", ".join("%.12g" % x for x in v))
    yaml = "%%YAML:1.0\n---\nwidth: 1242\nheight: 375\nK: %sbaseline: %.12g\nT_cam_lidar: %s" % (
        matrix(3, K), (p2[3] - p3[3]) / p2[0], matrix(4, T))
    write(out, "fuzz_yaml_calib", "calib.yaml", yaml)

    write(out, "fuzz_png", "gray8.png", png(7, 5, 8, [bytes(range(r * 7, r * 7 + 7)) for r in range(5)]))
    write(out, "fuzz_png", "disparity16.png", png(5, 3, 16, [struct.pack(">5H", *range(r * 300, r * 300 + 5)) for r in range(3)]))
    with open(os.path.join(SAMPLE, "mask", "000000.png"), "rb") as f:
        write(out, "fuzz_png", "mask.png", f.read())

    for i, line in enumerate(["in.pcd\0out.pcd\0-alpha\0000.5", "--disparities=128\0-v\0a.bin\0b.pcd",
                              "-format\0compressed\0-image_size\0001242x375\0x.bin\0y.pcd", "-h"]):
        write(out, "fuzz_arguments", "args%d" % i, line)


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
