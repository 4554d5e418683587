#!/usr/bin/python3
"""The PVD series spans a resumed run.

Runs 6 steps into A and keeps that checkpoint; resumes in A to step 10 (A's PVD lists
steps 0..10 once each); then continues from the step-6 checkpoint into B with a changed line
tension (a continuation). Asserts: B's surface.pvd lists A's snapshots up to the checkpoint's
time (by relative paths that exist), not A's later ones, followed by B's own, with strictly
increasing times.
Usage: test_output_series.py <membrane-flow> <small.prm>"""
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

exe, prm = sys.argv[1], sys.argv[2]
env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
work = tempfile.mkdtemp(prefix="membrane_series_")
a, b = os.path.join(work, "A"), os.path.join(work, "B")
common = ["--quiet", "--set", "Output/Interval=0", "--set", "Time stepping/End time=1", "--set", "Checkpoint/Interval=100"]


def run(*arguments):
    subprocess.run([exe, *common, *arguments, prm], check=True, env=env, stdout=subprocess.DEVNULL)


def series(directory):
    entries = ET.parse(os.path.join(directory, "surface.pvd")).getroot().findall(".//DataSet")
    return [(float(e.get("timestep")), e.get("file")) for e in entries]


def check(directory, earlier_prefix):
    entries = series(directory)
    times = [t for t, _ in entries]
    assert all(t1 > t0 for t0, t1 in zip(times, times[1:])), f"{directory}: times not increasing: {times}"
    for _, name in entries:
        assert os.path.isfile(os.path.join(directory, name)), f"{directory}: {name} does not exist"
    earlier = [name for _, name in entries if name.startswith(earlier_prefix)] if earlier_prefix else []
    return entries, earlier


run("--set", "Time stepping/Maximum steps=6", "--set", f"Output/Directory={a}")
shutil.copy(os.path.join(a, "checkpoint.txt"), os.path.join(a, "checkpoint-6.txt"))

run("--set", "Time stepping/Maximum steps=10", "--set", f"Output/Directory={a}",
    "--set", f"Checkpoint/Resume from={a}/checkpoint.txt")
entries, _ = check(a, None)
names = [name for _, name in entries]
assert len(names) == len(set(names)) == 11, f"A after resuming in place: {names}"

run("--set", "Time stepping/Maximum steps=14", "--set", f"Output/Directory={b}", "--set", "Material/Line tension=200",
    "--set", f"Checkpoint/Resume from={a}/checkpoint-6.txt")
entries, earlier = check(b, "../A/")
assert len(earlier) == 7, f"B lists {len(earlier)} of A's snapshots, expected 7 (steps 0..6): {entries}"
assert len(entries) == 7 + 8, f"B: {len(entries)} snapshots, expected 7 from A and steps 7..14 of its own"
assert entries[6][0] == series(a)[6][0], "the last of A's snapshots is not the checkpoint's time"
print(f"OK: A resumed in place lists 11 snapshots once each; B spans {len(entries)}: 7 of A, then its own")
