"""The static tet10 cantilever of scenes/cantilever.yaml as a CalculiX model on
the very mesh kerf reads: a gmsh .msh (format 2.2, second-order tetrahedra)
becomes C3D10 elements, linear elastic (E = 1 MPa, nu = 0.3, rho = 1000),
clamped at x = 0, under gravity; ccx prints the tip node's displacement.
Usage: cantilever_inp.py MESH.msh OUT.inp"""
import os, sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "../../../hyperelastic"))
from calculix import node_set, read_msh22, write_mesh, write_set  # noqa: E402

nodes, cells = read_msh22(sys.argv[1])
with open(sys.argv[2], "w") as out:
    write_mesh(out, nodes, cells)
    write_set(out, "FIXED", node_set(nodes, lambda x: abs(x[0]) < 1e-9))
    tip = min(nodes, key=lambda n: sum((a - b) ** 2 for a, b in zip(nodes[n], (0.1, 0.01, 0.01))))
    write_set(out, "TIP", [tip])
    out.write("*MATERIAL, NAME=TISSUE\n*ELASTIC\n1.0e6, 0.3\n*DENSITY\n1000.0\n"
              "*SOLID SECTION, ELSET=Eall, MATERIAL=TISSUE\n*BOUNDARY\nFIXED, 1, 3\n"
              "*STEP\n*STATIC\n*DLOAD\nEall, GRAV, 9.81, 0., 0., -1.\n*NODE PRINT, NSET=TIP\nU\n*END STEP\n")
