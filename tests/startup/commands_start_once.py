#!/usr/bin/python3
"""`kerf --version`, `kerf help` and `kerf check` run nothing on threads: the
process starts once (the thread policy's second start, core/thread_policy.h,
is for the commands that compute). `kerf run` still starts twice, the second
time with the policy's variables. Counted from the dynamic loader's own
trace (LD_DEBUG=files, inherited across exec): one "calling init" of libc
per start.
usage: commands_start_once.py KERF SCENE OUT"""
import subprocess, sys

kerf, scene, out = sys.argv[1:4]


def starts(arguments):
    done = subprocess.run([kerf] + arguments, capture_output=True, text=True,
                          env={"LD_DEBUG": "files", "PATH": "/usr/bin:/bin"})
    if done.returncode != 0:
        sys.exit(f"kerf {' '.join(arguments)} failed: {done.stderr[-2000:]}")
    return sum("calling init:" in line and "/libc.so" in line for line in done.stderr.splitlines())


failures = []
for arguments, expected in ((["--version"], 1), (["help"], 1), (["check", scene], 1),
                            (["run", scene, "--quiet", "--out", out, "--set", "output.vtk=false"], 2)):
    count = starts(arguments)
    print(f"kerf {arguments[0]}: started {count} time(s)")
    if count != expected:
        failures.append(f"kerf {' '.join(arguments)} started {count} times; expected {expected}")
if failures:
    sys.exit("\n".join(failures))
