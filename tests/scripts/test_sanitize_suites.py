#!/usr/bin/env python3
"""sanitize_suites.py (the sanitizer step's jobs), on fake suites: a whole suite becomes one job per
shard, never more shards than tests; a suite the selection holds only part of stays with ctest, as
do scripts; the scripts come first and the suites with the most tests next. Standard library only."""
import json
import os
import stat
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))


def fake_suite(folder, name, tests):
    """An executable that answers --gtest_list_tests as GoogleTest does."""
    path = os.path.join(folder, name)
    listing = "Suite.\\n" + "".join(f"  {t}\\n" for t in tests)
    with open(path, "w") as f:
        f.write(f"#!/bin/sh\nprintf '{listing}'\n")
    os.chmod(path, os.stat(path).st_mode | stat.S_IEXEC)
    return path


def gtest(executable, test, folder):
    return {"name": f"Suite.{test}", "command": [executable, f"--gtest_filter=Suite.{test}"],
            "properties": [{"name": "WORKING_DIRECTORY", "value": folder}]}


class SanitizeSuites(unittest.TestCase):
    def jobs(self, tests, shards):
        with tempfile.TemporaryDirectory() as folder:
            selection = os.path.join(folder, "tests.json")
            with open(selection, "w") as f:
                json.dump({"tests": tests(folder)}, f)
            out = os.path.join(folder, "jobs.txt")
            subprocess.run([sys.executable, os.path.join(HERE, "sanitize_suites.py"), selection, str(shards), out],
                           check=True)
            with open(out) as f:
                return [line.replace(folder, "F").split() for line in f.read().splitlines()]

    def test_whole_suites_in_shards_scripts_first_biggest_next(self):
        def tests(folder):
            big = fake_suite(folder, "big", ["a", "b", "c"])
            one = fake_suite(folder, "one", ["x"])
            return ([gtest(one, "x", folder)] + [gtest(big, t, folder) for t in "abc"] +
                    [{"name": "hostile_cases", "command": ["python3", "h.py"], "properties": []}])
        self.assertEqual(self.jobs(tests, 2), [
            ["ctest", "^hostile_cases$"],
            ["suite", "F/big", "F", "0", "2"],
            ["suite", "F/big", "F", "1", "2"],
            ["suite", "F/one", "F", "0", "1"],  # one test: one shard
        ])

    def test_a_partly_selected_suite_stays_with_ctest_by_exact_name(self):
        def tests(folder):
            part = fake_suite(folder, "part", ["a", "b"])
            return [gtest(part, "a", folder)]
        self.assertEqual(self.jobs(tests, 2), [["ctest", r"^Suite\.a$"]])


if __name__ == "__main__":
    unittest.main()
