"""The independent reference: CalculiX (ccx, from Debian) on the very mesh kerf
reads. A gmsh .msh (format 2.2, second-order tetrahedra) becomes a C3D10
model with `*HYPERELASTIC, NEO HOOKE` (kerf's `neohookean_uncoupled`: C10 =
mu/2, D1 = 2/K), solved static with NLGEOM; node sets are chosen by
coordinate, and the results are read back from ccx's .dat file."""
import os, re, subprocess

# gmsh's tet10 (mid-edge nodes on (0,1) (1,2) (0,2) (0,3) (2,3) (1,3)) to
# CalculiX's C3D10 ((1,2) (2,3) (3,1) (1,4) (2,4) (3,4)).
GMSH_TO_C3D10 = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]


def box_mesh(box, size, folder, name="body"):
    """A second-order gmsh mesh (format 2.2) of the box [0, box], made by the gmsh command; its path."""
    geo, msh = os.path.join(folder, name + ".geo"), os.path.join(folder, name + ".msh")
    open(geo, "w").write(f'SetFactory("OpenCASCADE");\nBox(1) = {{0, 0, 0, {box[0]}, {box[1]}, {box[2]}}};\n'
                         f"Mesh.CharacteristicLengthMax = {size};\nMesh.ElementOrder = 2;\n"
                         "Mesh.SecondOrderLinear = 1;\nMesh.MshFileVersion = 2.2;\n")
    subprocess.run(["gmsh", "-3", geo, "-o", msh], check=True, capture_output=True)
    return msh


def read_msh22(path):
    """Nodes {id: (x, y, z)} and tet10 cells (gmsh node order) of a format 2.2 file."""
    lines = open(path).read().split("\n")
    nodes, cells, i = {}, [], 0
    while i < len(lines):
        if lines[i] == "$Nodes":
            count = int(lines[i + 1])
            for line in lines[i + 2:i + 2 + count]:
                f = line.split()
                nodes[int(f[0])] = tuple(float(v) for v in f[1:4])
            i += count + 2
        elif lines[i] == "$Elements":
            count = int(lines[i + 1])
            for line in lines[i + 2:i + 2 + count]:
                f = [int(v) for v in line.split()]
                if f[1] == 11:  # 10-node tetrahedron
                    cells.append(f[3 + f[2]:])
            i += count + 2
        else:
            i += 1
    if not cells:
        raise ValueError(f"{path}: no second-order tetrahedra (gmsh type 11)")
    return nodes, cells


def node_set(nodes, where):
    return [n for n, x in nodes.items() if where(x)]


def write_set(out, name, ids):
    out.write(f"*NSET, NSET={name}\n")
    for k in range(0, len(ids), 12):
        out.write(", ".join(str(n) for n in ids[k:k + 12]) + "\n")


def write_mesh(out, nodes, cells):
    """The nodes (set Nall) and the C3D10 elements (set Eall) of an .inp file."""
    out.write("*NODE, NSET=Nall\n")
    for n, x in sorted(nodes.items()):
        out.write(f"{n}, {x[0]!r}, {x[1]!r}, {x[2]!r}\n")
    out.write("*ELEMENT, TYPE=C3D10, ELSET=Eall\n")
    for e, cell in enumerate(cells, 1):
        out.write(f"{e}, " + ", ".join(str(cell[k]) for k in GMSH_TO_C3D10) + "\n")


def run(msh, work, young, poisson, density, sets, boundary, loads, prints):
    """sets: {name: predicate on (x, y, z)}; boundary: lines of *BOUNDARY;
    loads: lines after the step's *STATIC (e.g. *DLOAD); prints: {set: 'U' or
    'RF'}. Returns {set: {node: (a, b, c)}} for U, {set: (a, b, c)} (totals) for RF."""
    nodes, cells = read_msh22(msh)
    mu = young / (2 * (1 + poisson))
    bulk = young / (3 * (1 - 2 * poisson))
    os.makedirs(work, exist_ok=True)
    inp = os.path.join(work, "model.inp")
    with open(inp, "w") as out:
        write_mesh(out, nodes, cells)
        for name, where in sets.items():
            ids = node_set(nodes, where)
            if not ids:
                raise ValueError(f"node set {name} is empty")
            write_set(out, name, ids)
        out.write(f"*MATERIAL, NAME=TISSUE\n*HYPERELASTIC, NEO HOOKE\n{mu / 2!r}, {2 / bulk!r}\n"
                  f"*DENSITY\n{density!r}\n*SOLID SECTION, ELSET=Eall, MATERIAL=TISSUE\n")
        out.write("*BOUNDARY\n" + "\n".join(boundary) + "\n")
        out.write("*STEP, NLGEOM, INC=1000\n*STATIC\n0.1, 1.0, 1e-6, 0.25\n")
        out.write("\n".join(loads) + "\n")
        for name, field in prints.items():
            out.write(f"*NODE PRINT, NSET={name}" + (", TOTALS=ONLY" if field == "RF" else "") + f"\n{field}\n")
        out.write("*END STEP\n")
    done = subprocess.run(["ccx", "-i", "model"], cwd=work, capture_output=True, text=True,
                          env=dict(os.environ, OMP_NUM_THREADS="2", CCX_NPROC_EQUATION_SOLVER="2"))
    if done.returncode != 0 or "Job finished" not in done.stdout:
        raise RuntimeError(f"ccx failed in {work}:\n{done.stdout[-2000:]}")
    return read_dat(os.path.join(work, "model.dat"), prints)


def read_dat(path, prints):
    """The last increment's blocks of the .dat file."""
    text = open(path).read()
    found = {}
    for name, field in prints.items():
        if field == "U":
            blocks = re.findall(rf"displacements \(vx,vy,vz\) for set {name.upper()} and time\s+(\S+)\n\n(.*?)(?:\n\n|\Z)",
                                text, re.S)
            rows = blocks[-1][1].strip().split("\n")
            found[name] = {int(r.split()[0]): tuple(float(v) for v in r.split()[1:4]) for r in rows}
        else:
            blocks = re.findall(rf"total force \(fx,fy,fz\) for set {name.upper()} and time\s+(\S+)\n\n(.*?)(?:\n\n|\Z)",
                                text, re.S)
            found[name] = tuple(float(v) for v in blocks[-1][1].split()[:3])
    return found
