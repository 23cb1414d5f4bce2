"""Every front end's outputs, byte for byte: the SHA-256 of what lidar_sgm_densify,
lidar_sgm_disparity, lidar_sgm_batch and the Python module write for data/sample and a KITTI 2015
frame with its raw scan, against the hashes in front_end_hashes.json. A change of structure (the
option table, the backends' interface, the readers) must not change one byte; a change of the
method changes these on purpose, and `--record` writes the new table (say why in CHANGELOG.md).

And every front end exposes every option of the library's table with the same default: each
tool's --help lists each option of its scope with the default lidar_sgm.options() gives, each tool
given every value option at that default writes the same bytes as without options, and so does
the Python Densifier given lidar_sgm.options() as keywords.

usage: front_end_hashes.py DENSIFY DISPARITY BATCH SAMPLE_DIR DATA_ROOT [--record]
The Python module is imported from PYTHONPATH. The KITTI cases are skipped (and said so) when
DATA_ROOT/kitti2015_lidar is absent.
"""
import hashlib
import json
import pathlib
import subprocess
import sys
import tempfile

TABLE = pathlib.Path(__file__).with_name("front_end_hashes.json")
KITTI_FRAME = "000007_10"


def sha256(path):
    return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()


def run(command):
    result = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, command))} failed:\n{result.stdout}\n{result.stderr}")


def frames(sample, data):
    """name -> (scan, left, right, calib) of each frame the cases run on."""
    out = {"sample": (sample / "velodyne/000000.bin", sample / "image_2/000000.png", sample / "image_3/000000.png",
                      sample / "calib/000000.txt")}
    kitti = data / "kitti2015_lidar"
    if kitti.is_dir():
        out["kitti"] = (kitti / f"velodyne/{KITTI_FRAME}.bin", kitti / f"image_2/{KITTI_FRAME}.png",
                        kitti / f"image_3/{KITTI_FRAME}.png", kitti / "calib/calib_cam_to_cam.txt")
    return out


def tool_cases(densify, disparity, batch, sample, data, out):
    """name -> file written by a command-line tool."""
    written = {}
    for name, (scan, left, right, calib) in frames(sample, data).items():
        cloud = out / f"densify_{name}.pcd"
        depth = out / f"densify_{name}_depth.png"
        run([densify, scan, cloud, "-calib", calib, "-left", left, "-right", right, "-depth", depth])
        written[f"densify fused {name} cloud"] = cloud
        written[f"densify fused {name} depth"] = depth
        lidar_only = out / f"densify_lidar_only_{name}.ply"
        run([densify, scan, lidar_only, "-calib", calib, "-left", left, "-scale", "0.5"])
        written[f"densify LiDAR-only half scale {name} cloud"] = lidar_only
        listing = out / f"list_{name}.txt"
        listing.write_text(f"{scan} {left} {right} {calib}\n")
        batch_out = out / f"batch_{name}"
        run([batch, "-list", listing, "-output_dir", batch_out, "-jobs", "1"])
        written[f"batch fused {name} cloud"] = batch_out / f"{scan.stem}.pcd"
    left, right = sample / "image_2/000000.png", sample / "image_3/000000.png"
    fused = out / "disparity_fused.png"
    confidence = out / "disparity_fused_confidence.png"
    run([disparity, left, right, fused, "-lidar", sample / "lidar_disp/000000.png", "-confidence", confidence])
    written["disparity fused sample"] = fused
    written["disparity fused sample confidence"] = confidence
    stereo = out / "disparity_stereo.png"
    run([disparity, left, right, stereo])
    written["disparity stereo-only sample"] = stereo
    return written


def default_text(value):
    """A default as the tools print it: 1.0 -> "1", 0.7 -> "0.7", "lidar" -> "lidar"."""
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


def help_defaults(tool, options):
    """Each option of `options` (name -> default) must be in the tool's --help, with its default."""
    result = subprocess.run([str(tool), "--help"], capture_output=True, text=True, check=True)
    help_text = result.stdout
    errors = []
    for name, value in options.items():
        start = help_text.find(f"\n  -{name} ")  # the option's own line, not a mention in another's
        if start < 0:
            start = help_text.find(f"\n  -{name}\n")
        if start < 0:
            errors.append(f"{tool.name} --help does not list -{name}")
            continue
        if isinstance(value, bool):
            continue  # a flag's text says what happens without it
        end = help_text.find("\n  -", start + 1)
        entry = " ".join(help_text[start:end].split())  # the help wraps its lines; a default is never split
        wanted = f"(default: {default_text(value)})"
        if wanted not in entry:
            errors.append(f"{tool.name} --help: -{name} does not say {wanted}: {entry}")
    return errors


def explicit_defaults(options):
    """Every value option at its default, as a command line."""
    line = []
    for name, value in options.items():
        if not isinstance(value, bool):
            line += [f"-{name}", default_text(value)]
    return line


def default_cases(densify, disparity, batch, sample, out):
    """Outputs of the tools and the Python module given every option at its default, and the
    errors of the tools' help, for data/sample: name -> file, errors."""
    import lidar_sgm
    cloud_options = lidar_sgm.options(cloud=True)
    disparity_options = lidar_sgm.options(cloud=False)
    errors = help_defaults(densify, cloud_options) + help_defaults(batch, cloud_options)
    errors += help_defaults(disparity, disparity_options)
    scan, left, right, calib = frames(sample, pathlib.Path("/nonexistent"))["sample"]
    written = {}
    cloud = out / "defaults_densify.pcd"
    run([densify, scan, cloud, "-calib", calib, "-left", left, "-right", right] + explicit_defaults(cloud_options))
    written["densify fused sample cloud"] = cloud
    listing = out / "defaults_list.txt"
    listing.write_text(f"{scan} {left} {right} {calib}\n")
    run([batch, "-list", listing, "-output_dir", out / "defaults_batch", "-jobs", "1"] +
        explicit_defaults(cloud_options))
    written["batch fused sample cloud"] = out / "defaults_batch" / f"{scan.stem}.pcd"
    fused = out / "defaults_disparity.png"
    run([disparity, left, right, fused, "-lidar", sample / "lidar_disp/000000.png"] +
        explicit_defaults(disparity_options))
    written["disparity fused sample"] = fused
    result = lidar_sgm.Densifier(lidar_sgm.read_calibration(str(calib)), **cloud_options).densify(
        lidar_sgm.read_kitti_bin(str(scan)), lidar_sgm.read_image(str(left)), lidar_sgm.read_image(str(right)))
    path = out / "defaults_python.pcd"
    lidar_sgm.write_cloud(str(path), result)
    written["python Densifier fused sample cloud"] = path
    return written, errors


def python_cases(sample, data, out):
    """name -> file written through the Python module."""
    import numpy as np
    import lidar_sgm
    written = {}
    for name, (scan, left, right, calib) in frames(sample, data).items():
        images = (lidar_sgm.read_image(str(left)), lidar_sgm.read_image(str(right)))
        result = lidar_sgm.Densifier(lidar_sgm.read_calibration(str(calib))).densify(
            lidar_sgm.read_kitti_bin(str(scan)), *images)
        path = out / f"python_{name}.pcd"
        lidar_sgm.write_cloud(str(path), result)
        written[f"python Densifier fused {name} cloud"] = path
        depth = out / f"python_{name}_depth.npy"
        np.save(depth, result.depth)
        written[f"python Densifier fused {name} depth"] = depth
    lidar_disparity = lidar_sgm.read_image(str(sample / "lidar_disp/000000.png")).astype(np.float32) / 256.0
    lidar_disparity[lidar_disparity == 0] = np.nan
    match = lidar_sgm.match(lidar_sgm.read_image(str(sample / "image_2/000000.png")),
                            lidar_sgm.read_image(str(sample / "image_3/000000.png")), lidar_disparity=lidar_disparity)
    path = out / "python_match.npy"
    np.save(path, match)
    written["python match fused sample disparity"] = path
    return written


def main(argv):
    record = "--record" in argv
    args = [a for a in argv if a != "--record"]
    if len(args) != 5:
        sys.exit(__doc__)
    densify, disparity, batch = (pathlib.Path(a) for a in args[:3])
    sample, data = pathlib.Path(args[3]), pathlib.Path(args[4])
    with tempfile.TemporaryDirectory() as folder:
        out = pathlib.Path(folder)
        written = tool_cases(densify, disparity, batch, sample, data, out)
        written.update(python_cases(sample, data, out))
        hashes = {name: sha256(path) for name, path in sorted(written.items())}
        defaults, errors = ({}, []) if record else default_cases(densify, disparity, batch, sample, out)
        for name, path in sorted(defaults.items()):
            same = sha256(path) == hashes[name]
            print(f"{'ok  ' if same else 'DIFF'} {name}, every option given at its default")
            if not same:
                errors.append(f"{name}: every option at its default changes the output")
    if record:
        TABLE.write_text(json.dumps(hashes, indent=2) + "\n")
        print(f"recorded {len(hashes)} hashes in {TABLE}")
        return 0
    expected = json.loads(TABLE.read_text())
    failures = [f"{name}: {hashes[name]} != recorded {expected.get(name)}" for name in hashes
                if hashes[name] != expected.get(name)]
    skipped = sorted(set(expected) - set(hashes))
    for name in hashes:
        print(f"{'ok  ' if hashes[name] == expected.get(name) else 'DIFF'} {name}")
    if skipped:
        print(f"skipped (no {data / 'kitti2015_lidar'}): {', '.join(skipped)}")
    failures += errors
    if failures:
        print("\n".join(failures), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
