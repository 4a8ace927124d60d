#!/usr/bin/python3
"""Implicit steps idle and beside one CPU-bound process, with kerf's thread
policy (now), as before it (libgomp's default spinning wait, threads
capped at the cores), and with a short spin the user may set (GOMP_SPINCOUNT
1 000, 10 000, 30 000, which kerf keeps): the soft block's neo-Hookean FEM step (1,308 nodes) from
`kerf run`, and the benchmark's corotational step (6,786 nodes) beside its
floor, a bare CHOLMOD factorization of the same matrix in the same run.
Interleaved repetitions; medians. usage (from the source tree, idle machine):
    results/threads/measure.py build [repetitions] > results/threads/threads.csv"""
import json, os, subprocess, sys, tempfile, statistics

build = sys.argv[1]
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 3
here = os.path.dirname(os.path.abspath(__file__))
variants = {"before": {"KERF_THREAD_POLICY": "off", "OMP_THREAD_LIMIT": str(os.cpu_count())}, "now": {},
            # a short spin before sleeping (libgomp spins GOMP_SPINCOUNT pause instructions; the default is 300 000)
            "spin 1000": {"GOMP_SPINCOUNT": "1000"}, "spin 10000": {"GOMP_SPINCOUNT": "10000"},
            "spin 30000": {"GOMP_SPINCOUNT": "30000"}}


def environment(extra):
    env = {k: v for k, v in os.environ.items()
           if k not in ("OMP_WAIT_POLICY", "OMP_NUM_THREADS", "OMP_THREAD_LIMIT", "GOMP_SPINCOUNT", "KERF_THREAD_POLICY")}
    env.update(extra)
    return env


def soft_block(env):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([f"{build}/cli/kerf", "run", f"{here}/soft_block_implicit.yaml", "--out", out, "--quiet"],
                       env=env, check=True)
        s = json.load(open(f"{out}/summary.json"))
    t = s["timing"]
    return {"soft_block_step_ms": t["step_ms"]["median"],
            "soft_block_factorization_ms": 1e3 * t["phases"]["factorize_s"] / max(1, s["solver"]["factorizations"]),
            "threads": s["parallel"]["threads"]["count"], "wait": s["parallel"]["threads"]["wait_policy"]}


def corotational(env):
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        subprocess.run([f"{build}/tests/kerf_benchmarks",
                        "--benchmark_filter=BM_ImplicitEulerStepCorotationalCholmod/2|BM_CholmodFactorization/2",
                        "--benchmark_repetitions=3", f"--benchmark_out={out.name}", "--benchmark_out_format=json"],
                       env=env, check=True, capture_output=True)
        rows = json.load(open(out.name))["benchmarks"]
    median = {r["run_name"]: r for r in rows if r.get("aggregate_name") == "median"}
    step = next(v for k, v in median.items() if "Corotational" in k)
    floor = next(v for k, v in median.items() if "Factorization" in k)
    return {"corotational_step_ms": step["median_step_ms"], "cholmod_factorization_floor_ms": floor["real_time"]}


rows = []
for rep in range(reps):
    for load in ("idle", "busy"):
        hog = subprocess.Popen(["/bin/sh", "-c", "while :; do :; done"]) if load == "busy" else None
        try:
            for name, extra in variants.items():
                env = environment(extra)
                row = {"variant": name, "load": load, "repetition": rep}
                row.update(soft_block(env))
                row.update(corotational(env))
                rows.append(row)
                print(row, file=sys.stderr)
        finally:
            if hog:
                hog.kill()
                hog.wait()
keys = list(rows[0].keys())
print(",".join(keys))
for r in rows:
    print(",".join(str(r[k]) for k in keys))
print("# medians over the repetitions", file=sys.stderr)
for name in variants:
    for load in ("idle", "busy"):
        sel = [r for r in rows if r["variant"] == name and r["load"] == load]
        print(name, load, {k: round(statistics.median(r[k] for r in sel), 1) for k in
                           ("soft_block_step_ms", "soft_block_factorization_ms", "corotational_step_ms",
                            "cholmod_factorization_floor_ms")}, file=sys.stderr)
