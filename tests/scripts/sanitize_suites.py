#!/usr/bin/env python3
"""Turns a ctest selection (ctest -N --show-only=json-v1) into the jobs of scripts/test_sanitizers.sh,
one per line, for a pool of SHARDS workers:

  ctest REGEX                            tests that are not GoogleTest suites (scripts), by name
  suite EXECUTABLE FOLDER INDEX TOTAL    shard INDEX of TOTAL of a GoogleTest suite, run whole

Each suite is cut into SHARDS shards (GoogleTest's GTEST_SHARD_INDEX / GTEST_TOTAL_SHARDS), so that
the longest suite does not keep one worker busy while the others wait; the scripts come first, then
the shards of the suites with the most tests. A GoogleTest test is one whose command is an
executable followed by --gtest_filter=...; a suite is run whole only when the selection holds all
of its tests, else its tests stay with ctest.
Usage: sanitize_suites.py TESTS.json SHARDS JOBS.txt
"""
import collections
import json
import re
import subprocess
import sys


def regex(name):
    return "^" + re.sub(r"([][.*+?^$|()\\{}])", r"\\\1", name) + "$"


def main():
    tests_json, shards, jobs_txt = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    with open(tests_json) as f:
        tests = json.load(f)["tests"]
    per_executable = collections.defaultdict(list)
    folders = {}
    scripts = []
    for test in tests:
        command = test.get("command") or []
        properties = {p["name"]: p["value"] for p in test.get("properties", [])}
        if len(command) >= 2 and command[1].startswith("--gtest_filter="):
            per_executable[command[0]].append(test["name"])
            folders[command[0]] = properties.get("WORKING_DIRECTORY", ".")
        else:
            scripts.append(test["name"])
    suites = []
    for executable, names in per_executable.items():
        listed = subprocess.run([executable, "--gtest_list_tests"], capture_output=True, text=True, check=True).stdout
        total = sum(1 for line in listed.splitlines() if line.startswith("  "))
        if total == len(names):
            suites.append((len(names), executable))
        else:  # part of a suite: leave those tests to ctest
            scripts.extend(names)
    suites.sort(reverse=True)
    with open(jobs_txt, "w") as f:
        if scripts:
            f.write("ctest " + "|".join(regex(name) for name in scripts) + "\n")
        for count, executable in suites:
            for index in range(min(shards, count)):
                f.write(f"suite {executable} {folders[executable]} {index} {min(shards, count)}\n")


if __name__ == "__main__":
    main()
