"""kerf from Python: load a scene (a file or a dict), override keys, run it,
and get the summary as a dict and the body's points and fields as numpy
arrays; run the studies. Errors are kerf.Error, carrying kerf's message
(file, line, key, value and what was expected).

    import kerf
    result = kerf.run("scenes/cantilever.yaml", ["discretization.fem.element=tet4"], out="/tmp/c")
    result.probes["tip"]["displacement"], result.displacement.shape
"""
import os

# CHOLMOD opens OpenMP regions of a fixed 4 threads; libgomp honours only
# OMP_THREAD_LIMIT, read when it loads (as the `kerf` command does: its
# factorizations are then the command's, digit for digit). Too late if
# another module loaded libgomp first (numpy with OpenMP OpenBLAS): import
# kerf first, or set OMP_THREAD_LIMIT yourself.
os.environ.setdefault("OMP_THREAD_LIMIT", str(os.cpu_count() or 1))

from ._kerf import Error, Result, Scene, __version__, load_scene, run, studies, study  # noqa: E402

__all__ = ["Error", "Result", "Scene", "__version__", "load_scene", "run", "studies", "study"]
