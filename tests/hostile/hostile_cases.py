#!/usr/bin/env python3
"""The hostile cases, run through lidar_sgm_densify as a user would run it.

Every case must end with exit code 1 (SIGTERM: killed by the signal), print "Error: " and the
problem, leave the output that was there before untouched and no temporary behind, within 10 s
and 2 GB of memory (the largest resident size the kernel reports for the tool's process).
Prints the table docs/RELIABILITY.md quotes; exits non-zero when a case breaks a rule.

Usage: hostile_cases.py DENSIFY_TOOL SAMPLE_DIR HOSTILE_DIR [--table OUT.md]
Standard library only.
"""
import os
import re
import resource
import shutil
import signal
import struct
import subprocess
import sys
import tempfile
import time
import zlib

# Under ASan + UBSan (scripts/test_sanitizers.sh sets ASAN_OPTIONS) the tool runs several times
# slower and its shadow memory is not the tool's own: the time limit is scaled, the memory one off.
SANITIZED = bool(os.environ.get("ASAN_OPTIONS"))
MAX_SECONDS = 10.0 * (5 if SANITIZED else 1)
MAX_RSS_BYTES = 2 * 1024 ** 3
PRECIOUS = b"precious: a file the user had before the run\n"


def png_bytes(width, height, row=None):
    """An 8-bit gray PNG of width x height, every row `row` (zeros by default), made by hand."""
    raw_row = b"\x00" + (row if row is not None else bytes(width))
    compressor = zlib.compressobj(9)
    data = b"".join(compressor.compress(raw_row) for _ in range(height)) + compressor.flush()

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", data) + chunk(b"IEND", b"")


def corpus_cases(hostile_dir):
    """The regression corpus: each file of tests/data/hostile/README.md's table, as the scan or image."""
    cases = []
    with open(os.path.join(hostile_dir, "README.md"), encoding="utf-8") as readme:
        for line in readme:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) == 3 and re.match(r"^[A-Za-z0-9_]+\.(pcd|ply|bin)$", cells[0]):
                cases.append((cells[0], ["{hostile}/" + cells[0], "{out}", "-calib", "{calib}", "-left", "{left}"],
                              cells[2].strip("`")))
            elif len(cells) == 3 and re.match(r"^[A-Za-z0-9_]+\.png$", cells[0]):  # an image: the left one
                cases.append((cells[0], ["{scan}", "{out}", "-calib", "{calib}", "-left", "{hostile}/" + cells[0]],
                              cells[2].strip("`")))
    return cases


def prepare_inputs(work, sample):
    """Hostile inputs made at run time: too big to ship, or derived from the sample."""
    inputs = os.path.join(work, "inputs")
    os.makedirs(inputs)
    # A 30000 x 30000 PNG of about 1 MB (the issue's: 8.6 GB and 24 s before std::bad_alloc).
    with open(os.path.join(inputs, "huge.png"), "wb") as f:
        f.write(png_bytes(30000, 30000))
    with open(os.path.join(inputs, "one_row.png"), "wb") as f:
        f.write(png_bytes(1242, 1))
    calib = open(os.path.join(sample, "calib", "000000.txt"), encoding="utf-8").read()
    # fx = 1e-300 (accepted before: a 3.8e302 m baseline, 421 k points written).
    tiny = re.sub(r"^P2: \S+", "P2: 1e-300", calib, flags=re.M)
    tiny = re.sub(r"^P3: \S+", "P3: 1e-300", tiny, flags=re.M)
    with open(os.path.join(inputs, "fx_tiny.txt"), "w", encoding="utf-8") as f:
        f.write(tiny)
    yaml = {
        "nested.yaml": "%YAML:1.0\n" + "[" * 100000 + "\n",
        "huge_matrix.yaml": "%YAML:1.0\nwidth: 1242\nheight: 375\nbaseline: 0.54\n"
                            "K: !!opencv-matrix\n  rows: 100000\n  cols: 100000\n  dt: d\n  data: [1]\n",
        "big.yaml": "%YAML:1.0\n#" + "x" * (2 * 1024 * 1024) + "\n",
        "binary.yaml": "%YAML:1.0\nwidth: \x00\x01\x02\n",
    }
    for name, text in yaml.items():
        with open(os.path.join(inputs, name), "w", encoding="utf-8") as f:
            f.write(text)
    with open(os.path.join(inputs, "truncated.bin"), "wb") as f:
        f.write(bytes(100))
    with open(os.path.join(inputs, "nan.bin"), "wb") as f:
        f.write(struct.pack("<4f", float("nan"), float("inf"), 0.0, 0.0) * 100)
    with open(os.path.join(inputs, "behind.bin"), "wb") as f:
        f.write(b"".join(struct.pack("<4f", -10.0 - i * 0.1, 0.0, -0.5, 0.0) for i in range(100)))
    with open(os.path.join(inputs, "empty.bin"), "wb") as f:
        pass
    with open(os.path.join(inputs, "small.png"), "wb") as f:
        f.write(png_bytes(1000, 300))
    return inputs


def generated_cases():
    scan, calib, pair = "{scan}", "{calib}", ["-left", "{left}", "-right", "{right}"]
    return [
        ("PNG of 30000x30000 px", [scan, "{out}", "-calib", calib, "-left", "{inputs}/huge.png"],
         "more than the limit of 16384x16384"),
        ("-image_size 100000x100000", [scan, "{out}", "-calib", calib, "-image_size", "100000x100000"],
         "option -image_size: '100000x100000' is larger than the limit"),
        ("calibration with fx = 1e-300", [scan, "{out}", "-calib", "{inputs}/fx_tiny.txt"] + pair,
         "focal length"),
        ("YAML nested 100000 deep", [scan, "{out}", "-calib", "{inputs}/nested.yaml"] + pair, "nested.yaml"),
        ("YAML 100000x100000 matrix, 1 value", [scan, "{out}", "-calib", "{inputs}/huge_matrix.yaml"] + pair,
         "huge_matrix.yaml"),
        ("YAML of 2 MB", [scan, "{out}", "-calib", "{inputs}/big.yaml"] + pair, "big.yaml"),
        ("YAML with control bytes", [scan, "{out}", "-calib", "{inputs}/binary.yaml"] + pair, "binary.yaml"),
        ("1-row image", [scan, "{out}", "-calib", calib, "-left", "{inputs}/one_row.png"],
         "is 1242x1: an image needs at least 2x2 pixels"),
        ("images of different sizes", [scan, "{out}", "-calib", calib, "-left", "{left}", "-right",
                                       "{inputs}/small.png"], "but the right image is 1000x300"),
        ("KITTI .bin of 100 bytes", ["{inputs}/truncated.bin", "{out}", "-calib", calib] + pair,
         "is not a multiple of 16"),
        ("empty .bin", ["{inputs}/empty.bin", "{out}", "-calib", calib] + pair, "has no points"),
        ("only NaN/Inf points", ["{inputs}/nan.bin", "{out}", "-calib", calib] + pair, "NaN/Inf"),
        ("every point behind the camera", ["{inputs}/behind.bin", "{out}", "-calib", calib] + pair,
         "behind the camera"),
        ("missing scan", ["{inputs}/missing.bin", "{out}", "-calib", calib] + pair, "no such file"),
        ("-max_points below the scan", [scan, "{out}", "-calib", calib, "-max_points", "1000"] + pair,
         "more than the limit of 1000 points"),
        ("impossible parameter -alpha 2", [scan, "{out}", "-calib", calib, "-alpha", "2"] + pair, "alpha = 2"),
        ("output is a folder", [scan, "{out}", "-calib", calib, "-color", "{outdir}/folder.png"] + pair,
         "it is a folder"),
        ("output in a missing folder", [scan, "{out}", "-calib", calib, "-color", "{outdir}/no/c.png"] + pair,
         "does not exist"),
        ("output in an unwritable folder", [scan, "{out}", "-calib", calib, "-color", "/proc/c.png"] + pair,
         "is not writable"),
        ("an output is an input", [scan, "{out}", "-calib", calib, "-left", "{left_copy}", "-disparity",
                                   "{left_copy}"], "refusing to overwrite an input"),
        # Written after the cloud: the second picture hits the file-size limit (SIGXFSZ ignored).
        ("a later output fails to write", [scan, "{out}", "-calib", calib, "-left", "{left}", "-voxel", "2",
                                           "-disparity", "{outdir}/d.png", "-color", "{outdir}/c.png"],
         "no output was replaced", {"file_size_limit": 64 * 1024}),
        ("SIGTERM while saving", [scan, "{out}", "-calib", calib, "-left", "{left}", "-format", "ascii",
                                  "-disparity", "{outdir}/d.png"], None, {"sigterm_at": "Saving"}),
    ]


def run_case(tool, arguments, options, outdir):
    """Runs the tool; returns (exit status or -signal, output, seconds, max RSS bytes)."""
    limit = options.get("file_size_limit")

    def before_exec():
        if limit:
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # the write fails with EFBIG instead
            resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    log_path = os.path.join(os.path.dirname(outdir), "log.txt")
    start = time.monotonic()
    with open(log_path, "wb") as log:
        process = subprocess.Popen([tool] + arguments, stdout=log, stderr=subprocess.STDOUT, preexec_fn=before_exec)
        if "sigterm_at" in options:
            deadline = time.monotonic() + MAX_SECONDS
            while time.monotonic() < deadline and process.poll() is None:
                with open(log_path, "rb") as partial:
                    if options["sigterm_at"].encode() in partial.read():
                        break
                time.sleep(0.02)
            if process.poll() is None:
                process.send_signal(signal.SIGTERM)
        try:
            _, status, usage = os.wait4(process.pid, 0)
        except ChildProcessError:
            status, usage = 0, None
        process.returncode = 0  # reaped above
    seconds = time.monotonic() - start
    code = os.waitstatus_to_exitcode(status)
    with open(log_path, "rb") as log:
        output = log.read().decode("utf-8", "replace")
    return code, output, seconds, (usage.ru_maxrss * 1024 if usage else 0)


def main():
    args = sys.argv[1:]
    table_path = None
    if "--table" in args:
        i = args.index("--table")
        table_path = args[i + 1]
        del args[i:i + 2]
    if len(args) != 3:
        sys.exit(__doc__)
    tool, sample, hostile = (os.path.abspath(a) for a in args)
    work = tempfile.mkdtemp(prefix="lidar_sgm_hostile_%d_" % os.getpid())
    failures = []
    rows = []
    try:
        inputs = prepare_inputs(work, sample)
        left_copy = os.path.join(work, "left_copy.png")
        shutil.copyfile(os.path.join(sample, "image_2", "000000.png"), left_copy)
        cases = [(name, argv, message, {}) for name, argv, message in corpus_cases(hostile)]
        cases += [c if len(c) == 4 else c + ({},) for c in generated_cases()]
        for index, (name, argv, message, options) in enumerate(cases):
            outdir = os.path.join(work, "out%02d" % index)
            os.makedirs(os.path.join(outdir, "folder.png"))
            for output in ("out.pcd", "d.png"):
                with open(os.path.join(outdir, output), "wb") as f:
                    f.write(PRECIOUS)
            values = {"scan": os.path.join(sample, "velodyne", "000000.bin"),
                      "calib": os.path.join(sample, "calib", "000000.txt"),
                      "left": os.path.join(sample, "image_2", "000000.png"),
                      "right": os.path.join(sample, "image_3", "000000.png"),
                      "out": os.path.join(outdir, "out.pcd"), "outdir": outdir, "inputs": inputs,
                      "hostile": hostile, "left_copy": left_copy}
            arguments = [a.format(**values) for a in argv]
            left_before = open(left_copy, "rb").read()
            code, output, seconds, rss = run_case(tool, arguments, options, outdir)
            problems = []
            if "sigterm_at" in options:
                if code != -signal.SIGTERM:
                    problems.append("ended with %d, not by SIGTERM" % code)
            else:
                if code != 1:
                    problems.append("exit code %d, not 1" % code)
                if "Error: " not in output:
                    problems.append("no 'Error: ' line")
                if message not in output:
                    problems.append("the message does not say '%s'" % message)
            for output_name in ("out.pcd", "d.png"):
                with open(os.path.join(outdir, output_name), "rb") as f:
                    if f.read() != PRECIOUS:
                        problems.append(output_name + " was replaced")
            left_behind = sorted(set(os.listdir(outdir)) - {"out.pcd", "d.png", "folder.png"})
            if left_behind:
                problems.append("left " + ", ".join(left_behind))
            if open(left_copy, "rb").read() != left_before:
                problems.append("an input was overwritten")
            if seconds > MAX_SECONDS:
                problems.append("took %.1f s" % seconds)
            if rss > MAX_RSS_BYTES and not SANITIZED:
                problems.append("used %.0f MB" % (rss / 2 ** 20))
            error = next((l for l in output.splitlines() if l.startswith("Error: ")), "(killed by SIGTERM)"
                         if code == -signal.SIGTERM else "(none)")
            for path, shown in ((work, "…"), (hostile, "tests/data/hostile"), (sample, "data/sample")):
                error = error.replace(path, shown)
            rows.append("| %s | %s | %s | %.2f | %.0f | %s |" % (
                name, "SIGTERM" if code == -signal.SIGTERM else code, error.replace("|", "\\|"), seconds,
                rss / 2 ** 20, "ok" if not problems else "; ".join(problems)))
            if problems:
                failures.append("%s: %s\n%s" % (name, "; ".join(problems), output))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    table = ("| case | exit | message | s | max RSS MB | rules |\n| --- | --- | --- | ---: | ---: | --- |\n" +
             "\n".join(rows) + "\n")
    print(table)
    if table_path:
        with open(table_path, "w", encoding="utf-8") as f:
            f.write(table)
    for failure in failures:
        print("FAILED " + failure, file=sys.stderr)
    print("%d cases, %d failed" % (len(rows), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
