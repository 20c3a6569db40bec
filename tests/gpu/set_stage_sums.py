#!/usr/bin/env python3
"""Sums the stage seconds and the merge steps of a boolean set's reports (FOLDER/*.json, written
by `strata boolean ... --report`), and the bytes of its files (FOLDER/*.stl): one line each."""
import glob
import json
import os
import sys

folder = sys.argv[1]
stages, steps, cases = {}, {}, 0
for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
    with open(path) as f:
        report = json.load(f)
    cases += 1
    for stage in report.get("stages", []):
        stages[stage["name"]] = stages.get(stage["name"], 0.0) + stage["seconds"]
    for step in report.get("merge_steps", []):
        steps[step["name"]] = steps.get(step["name"], 0.0) + step["seconds"]
size = sum(os.path.getsize(p) for p in glob.glob(os.path.join(folder, "*.stl")))
print("%s: %d cases, %.1f MB of STL; stages %s; merge steps %s" % (
    folder, cases, size / 1e6,
    ", ".join("%s %.3f" % kv for kv in stages.items()),
    ", ".join("%s %.3f" % kv for kv in steps.items())))
