"""A sweep from Python: the cantilever's tip deflection as its mesh is refined,
tet4 against tet10, plotted against the element size (matplotlib).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep_element_size.py OUT_DIR
"""
import os
import sys

import kerf  # first: it caps OpenMP before numpy loads it

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENE = os.path.join(os.path.dirname(__file__), "..", "..", "scenes", "cantilever.yaml")
SIZES = [0.01, 0.0075, 0.005, 0.004]  # m


def tip_deflection(element, size, out):
    result = kerf.run(SCENE, [f"discretization.fem.element={element}", f"discretization.fem.size={size}",
                              "output.vtk=false"], out=out)
    return -result.probes["tip"]["displacement"][2], result.summary["counts"]["nodes"]


def main(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    plt.figure(figsize=(5, 3.5))
    for element in ("tet4", "tet10"):
        deflections = []
        for size in SIZES:
            w, nodes = tip_deflection(element, size, os.path.join(out_dir, f"{element}_{size}"))
            print(f"{element} size {size * 1000:g} mm: {nodes} nodes, tip deflection {w * 1000:.4f} mm")
            deflections.append(w * 1000)
        plt.plot([s * 1000 for s in SIZES], deflections, "o-", label=element)
    plt.xlabel("element size (mm)")
    plt.ylabel("tip deflection (mm)")
    plt.gca().invert_xaxis()
    plt.legend()
    plt.title("cantilever under its own weight")
    plt.tight_layout()
    plt.savefig(os.path.join(out_dir, "sweep_element_size.png"), dpi=120)
    print("plot:", os.path.join(out_dir, "sweep_element_size.png"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sweep_element_size")
