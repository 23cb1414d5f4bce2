#!/usr/bin/env python3
"""Splits a ctest selection (ctest -N --show-only=json-v1) for scripts/test_sanitizers.sh: the
GoogleTest suites, one line per executable ("EXECUTABLE WORKING_FOLDER", most tests first, so that
the longest start first), and the other tests by name (anchored regexes, one per line).

A GoogleTest test is one whose command is an executable followed by --gtest_filter=...; a suite
is run whole only when the selection holds all of its tests, else its tests stay with ctest.
Usage: sanitize_suites.py TESTS.json SUITES.txt SCRIPTS.txt
"""
import collections
import json
import re
import subprocess
import sys


def main():
    tests_json, suites_txt, scripts_txt = sys.argv[1:4]
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
    with open(suites_txt, "w") as f:
        for _, executable in suites:
            f.write(f"{executable} {folders[executable]}\n")
    with open(scripts_txt, "w") as f:
        for name in scripts:
            f.write("^" + re.sub(r"([][.*+?^$|()\\{}])", r"\\\1", name) + "$\n")


if __name__ == "__main__":
    main()
