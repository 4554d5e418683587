#!/usr/bin/python3
"""Every command in README.md, docs/*.md and benchmarks/README.md runs as written.

The shell commands of the ```sh blocks are run, one by one, from a scratch copy of the
repository's tracked files, so that docs cannot drift from the program. In the copy,
build/membrane-flow (also first on PATH as `membrane-flow`) runs the real program with at most
3 time steps, so that whole studies finish in seconds: the test checks that each command, its
options, files and scripts exist and work together, not the science. Each command must exit
with 0 (or the code listed in EXPECTED_CODES, with the reason).

The commands run in the order of the documents (README first), as a reader would, so a
command may use the results of an earlier one; the stand-in adds --overwrite, so a command
that runs into a directory an earlier one wrote is not refused. A shell variable set by an
assignment line (R=...) holds for the rest of its block. The Python module is importable as
after the setup command (PYTHONPATH points at the build), and its commands (python3 -m membrane_flow
...) run the stand-in (MEMBRANE_FLOW_EXE). Not run: ./scripts/setup.sh and ./scripts/test.sh (they install packages and run this suite).
A run with the same arguments, input file and working directory as an earlier command is not
repeated while its results are unchanged (scripts/run_experiments.sh runs the experiments that
docs/experiments.md lists one by one). bench_cahn_hilliard runs its 32 x 32 case only, briefly.
benchmarks/scaling.py runs with --sizes 16,32 in place of its documented sizes, mesh-convergence
with --levels 1 (and uniform meshes of 16, 24, 32), neck-resolution with --max-level 2 and the 4-rank sweep with 2 ranks (REDUCED).
Placeholders the docs use are created first: my_run.prm (experiments/default.prm),
my_sweep.json (two line tensions of 7.3) and hosts (an MPI host file for this machine).
Usage: test_docs_commands.py <source dir> <membrane-flow> <bench_cahn_hilliard> [<filter>]"""
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

source, exe, bench = (os.path.abspath(a) for a in sys.argv[1:4])
only = sys.argv[4] if len(sys.argv) > 4 else None
NOT_RUN = {"./scripts/setup.sh", "./scripts/test.sh"}
# With 3 time steps every run of a bisection ends flat: it then reports that both ends
# give the same outcome and exits with 1, as documented in docs/workflow.md.
MF = r"/usr/bin/python3 -m membrane_flow"
EXPECTED_CODES = {f"{MF} critical": 1}
MAX_STEPS = 3
# The scaling benchmark's own meshes (up to 256 x 256: minutes and gigabytes per case even
# for 3 steps) are replaced by the smallest sizes; its options and output are still run.
REDUCED = [(re.compile(r"^(benchmarks/scaling\.py .*)--sizes \S+"), r"\1--sizes 16,32"),
           # The studies with the most cases run their smallest set: each case still runs, 3 steps.
           (re.compile(rf"^({MF} mesh-convergence .*)--levels 1,2,3"), r"\1--levels 1"),
           (re.compile(rf"^({MF} mesh-convergence .*)--uniform \S+"), r"\1--uniform 16,24,32"),
           (re.compile(rf"^{MF} neck-resolution$"), f"{MF} neck-resolution --max-level 2"),
           # 4 ranks on a 2-core machine spend most of their time waiting for each other.
           (re.compile(rf"^({MF} sweep .*)--ranks 4"), r"\1--ranks 2")]


def commands(path):
    """Shell commands of the ```sh blocks of a Markdown file (continuation lines joined),
    each with the variable assignments made before it in its block."""
    text = open(path).read()
    for block in re.findall(r"```sh\n(.*?)```", text, re.S):
        assignments = []
        for command in block.replace("\\\n", " ").splitlines():
            command = re.sub(r"\s+#.*$", "", command.strip())
            if not command or command.startswith("#"):
                continue
            if re.fullmatch(r"[A-Za-z_][A-Za-z_0-9]*=\S*", command):
                assignments.append(command)
                continue
            yield "; ".join(assignments + [command])


def make_copy():
    work = tempfile.mkdtemp(prefix="membrane_docs_")
    files = subprocess.run(["git", "-C", source, "ls-files"], capture_output=True, text=True,
                           check=True).stdout.split()
    for name in files:
        os.makedirs(os.path.join(work, os.path.dirname(name)), exist_ok=True)
        if os.path.isfile(os.path.join(source, name)):
            shutil.copy2(os.path.join(source, name), os.path.join(work, name))
    os.makedirs(os.path.join(work, "build", "benchmarks"))
    # The benchmark runs its smallest mesh only, briefly: its options and output are checked.
    bench_wrapper = os.path.join(work, "build", "benchmarks", "bench_cahn_hilliard")
    with open(bench_wrapper, "w") as out:
        out.write(f'''#!/bin/sh
exec "{bench}" "$@" --benchmark_filter=/32$ --benchmark_min_time=0.01
''')
    os.chmod(bench_wrapper, 0o755)
    # The stand-in for the program. A run with the same arguments, input files and working
    # directory as an earlier command of this check (scripts/run_experiments.sh runs every
    # experiment that docs/experiments.md then lists one by one) is not repeated while the
    # directory it wrote still holds that run's summary.json: the program is deterministic, so a
    # second run would check nothing new; its output is printed again. Always run: runs under
    # mpirun, resumed runs (their result depends on the checkpoint), and runs whose output goes
    # to a file (the program then writes its log itself and must see that file as its stdout).
    memo = os.path.join(work, ".docs_runs")
    wrapper = os.path.join(work, "build", "membrane-flow")
    with open(wrapper, "w") as out:
        out.write(f'''#!/bin/bash
for a in "$@"; do
  case "$a" in --print-parameters*|--help|--version) exec "{exe}" "$@";; esac
done
run=("{exe}" "$@" --overwrite --set "Time stepping/Maximum steps={MAX_STEPS}")
[ -n "$OMPI_COMM_WORLD_SIZE$PMI_RANK" ] && exec "${{run[@]}}"
[ -f /proc/self/fd/1 ] && exec "${{run[@]}}"
files=()
for a in "$@"; do [ -f "$a" ] && files+=("$a"); done
printf '%s\\n' "$@" | grep -q "Resume from" && exec "${{run[@]}}"
[ ${{#files[@]}} -gt 0 ] && grep -Eq "Resume from *= *[^ ]" "${{files[@]}}" && exec "${{run[@]}}"
key=$( {{ pwd; printf '%s\\n' "$@" | grep -v -x -e --quiet -e --overwrite; [ ${{#files[@]}} -gt 0 ] && cat "${{files[@]}}"; }} | sha1sum | cut -c1-40)
if [ -f "{memo}/$key" ]; then
  dir=$(cat "{memo}/$key")
  if cmp -s "$dir/summary.json" "{memo}/$key.summary"; then
    cat "{memo}/$key.log"
    exit 0
  fi
fi
log=$(mktemp)
"${{run[@]}}" | tee "$log"
code=${{PIPESTATUS[0]}}
dir=$(sed -n 's/.*; output in \\(.*\\)\\/$/\\1/p' "$log" | head -n 1)
[ -d "$dir" ] && dir=$(cd -- "$dir" > /dev/null && pwd)
if [ "$code" -eq 0 ] && [ -f "$dir/summary.json" ]; then
  mkdir -p "{memo}"
  echo "$dir" > "{memo}/$key"
  cp "$dir/summary.json" "{memo}/$key.summary"
  cp "$log" "{memo}/$key.log"
fi
rm -f "$log"
exit "$code"
''')
    os.chmod(wrapper, 0o755)
    shutil.copy(os.path.join(work, "experiments", "default.prm"), os.path.join(work, "my_run.prm"))
    with open(os.path.join(work, "my_sweep.json"), "w") as out:
        json.dump({"base": "experiments/7.3-budding.prm", "output": "results/my_sweep",
                   "vary": {"Material/Line tension": [630, 1000]}}, out)
    with open(os.path.join(work, "hosts"), "w") as out:
        out.write("localhost slots=8\n")
    return work


documents = [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs", "*.md"))) + \
            [os.path.join(source, "benchmarks", "README.md")]
work = make_copy()
env = dict(os.environ, PATH=os.path.join(work, "build") + os.pathsep + os.environ["PATH"],
           OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1",
           OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1",
           PYTHONPATH=os.path.join(os.path.dirname(exe), "python"),
           MEMBRANE_FLOW_EXE=os.path.join(work, "build", "membrane-flow"))
failures, ran, seen = [], 0, set()
for document in documents:
    for command in commands(document):
        where = os.path.relpath(document, source)
        if command in NOT_RUN or command in seen or (only and only not in command):
            continue
        seen.add(command)
        start = time.time()
        run = command
        for pattern, replacement in REDUCED:
            run = pattern.sub(replacement, run)
        try:
            result = subprocess.run(["bash", "-c", run], cwd=work, env=env, capture_output=True, text=True,
                                    timeout=600)
            code, output = result.returncode, result.stdout + result.stderr
        except subprocess.TimeoutExpired:
            code, output = "timeout", ""
        expected = next((c for key, c in EXPECTED_CODES.items() if command.startswith(key)), 0)
        ran += 1
        status = "ok" if code in (0, expected) else "FAILED"
        print(f"{status:6s} {time.time() - start:5.1f} s  exit {code}  {where}: {command}", flush=True)
        if status != "ok":
            failures.append(f"{where}: {command}\n  exit {code}: " + "\n  ".join(output.strip().splitlines()[-8:]))

for failure in failures:
    print("\n" + failure)
print(f"{ran} commands run, {len(failures)} failed")
if failures:
    print(f"the scratch copy is kept for inspection: {work}")
else:
    shutil.rmtree(work, ignore_errors=True)
sys.exit(1 if failures or ran == 0 else 0)
