"""kerf from Python: load a scene (a file or a dict), override keys, run it,
and get the summary as a dict and the body's points and fields as numpy
arrays; run the studies. Errors are kerf.Error, carrying kerf's message
(file, line, key, value and what was expected).

    import kerf
    result = kerf.run("scenes/cantilever.yaml", ["discretization.fem.element=tet4"], out="/tmp/c")
    result.probes["tip"]["displacement"], result.displacement.shape

A session steps a run from Python, the state read between steps (numpy
views of kerf's memory):

    with kerf.Session("scenes/organ_cut.yaml", out="/tmp/o") as s:
        while not s.done:
            s.step()
            top = s.displacement[:, 2].max()
"""
import os

# libgomp reads its environment once, when it loads; set here as the `kerf`
# command sets it (core/thread_policy.h): no more threads than the cores this
# process may use (CHOLMOD opens regions of a fixed 4 otherwise), and threads
# that sleep at a barrier instead of spinning (a spinning thread holds the core
# another process or a preempted thread needs). Too late if another module
# loaded libgomp first (numpy with OpenMP OpenBLAS): import kerf first, or set
# them yourself. The summary's parallel.threads says what was in effect.
os.environ.setdefault("OMP_THREAD_LIMIT", str(len(os.sched_getaffinity(0)) or 1))
if "GOMP_SPINCOUNT" not in os.environ:
    os.environ.setdefault("OMP_WAIT_POLICY", "passive")

from ._kerf import (Error, Record, Result, Scene, Session, __version__, load_scene, read_outcome, run,  # noqa: E402
                    studies, study)

__all__ = ["Error", "Record", "Result", "Scene", "Session", "__version__", "load_scene", "read_outcome", "run",
           "studies", "study"]
