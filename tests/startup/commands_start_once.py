#!/usr/bin/python3
"""Every `kerf` command starts once: the launcher links no OpenMP, sets the
thread policy's variables (core/thread_policy.h) and then loads the program
(cli/launcher.cpp), instead of setting them and starting again. A run still
gets the policy (its summary: passive waiting, as many threads as the cores
given). The starts are counted from the dynamic loader's own trace
(LD_DEBUG=files, which an exec would inherit): one "calling init" of libc
per start.
usage: commands_start_once.py KERF SCENE OUT"""
import json, subprocess, sys

kerf, scene, out = sys.argv[1:4]
failures = []
if "libgomp" in subprocess.run(["ldd", kerf], capture_output=True, text=True, check=True).stdout:
    failures.append(f"{kerf} links libgomp (ldd): it would read its variables before kerf sets them")


def starts(arguments):
    done = subprocess.run([kerf] + arguments, capture_output=True, text=True,
                          env={"LD_DEBUG": "files", "PATH": "/usr/bin:/bin"})
    if done.returncode != 0:
        sys.exit(f"kerf {' '.join(arguments)} failed: {done.stderr[-2000:]}")
    return sum("calling init:" in line and "/libc.so" in line for line in done.stderr.splitlines())


for arguments in (["--version"], ["help"], ["check", scene], ["run", scene, "--quiet", "--out", out]):
    count = starts(arguments)
    print(f"kerf {arguments[0]}: started {count} time(s)")
    if count != 1:
        failures.append(f"kerf {' '.join(arguments)} started {count} times; expected once")
threads = json.load(open(f"{out}/summary.json"))["parallel"]["threads"]
print(f"kerf run: threads {threads}")
if threads["wait_policy"] != "passive" or threads["limited_by"] == "set outside kerf":
    failures.append(f"the run did not get the thread policy: {threads}")
if failures:
    sys.exit("\n".join(failures))
