"""ParaView's own readers (pvbatch) on every kind of kerf output: a cut
series (.pvd of the body's .vtu, the cut surface's .vtu and the Enrichment
Grid's .vti), a FEM cut series, a series of .pvtu pieces from two MPI ranks,
and a .vti alone. Each must hold its arrays at the last step (an array
missing fails), and a picture of each cut run must render.

    scripts/pvbatch.sh tests/paraview/check_outputs.py CUT_STUDY_DIR MPI_RUN_DIR SERIAL_RUN_DIR OUT_DIR
"""
import glob
import os
import sys

from paraview import servermanager
from paraview.simple import ExtractBlock, GetAnimationScene, OpenDataFile, PVDReader, PNGSeriesReader

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "scripts"))
import paraview_pictures  # noqa: E402

failures = []


def expect(condition, what):
    print(("ok   " if condition else "FAIL ") + what)
    if not condition:
        failures.append(what)


def last_step(reader):
    reader.UpdatePipelineInformation()
    time = reader.TimestepValues[-1] if reader.TimestepValues else 0.0
    GetAnimationScene().AnimationTime = time
    return time


def block(reader, name, time):
    part = ExtractBlock(Input=reader, Selectors=["/Root/" + name])
    part.UpdatePipeline(time)
    return part


def arrays(source):
    return set(source.PointData.keys()), set(source.CellData.keys())


def check_cut_series(pvd, body_cell_stress, grid):
    reader = PVDReader(FileName=pvd)
    time = last_step(reader)
    expect(len(reader.TimestepValues) >= 3, f"{pvd}: {len(reader.TimestepValues)} time steps")
    reader.UpdatePipeline(time)
    kind = reader.GetDataInformation().GetDataSetTypeAsString()
    expect(kind == "vtkMultiBlockDataSet", f"{pvd}: ParaView reads its parts as blocks (got {kind})")
    if kind != "vtkMultiBlockDataSet":
        return  # ExtractBlock on a single data set would crash pvbatch
    body = block(reader, "body", time)
    points, cells = arrays(body)
    expect(body.GetDataInformation().GetNumberOfPoints() > 0, f"{pvd}: the body has points")
    expect("displacement" in points, f"{pvd}: body point array displacement")
    stress_arrays = cells if body_cell_stress else points
    expect({"stress", "von_mises"} <= stress_arrays, f"{pvd}: body arrays stress, von_mises")
    cut = block(reader, "cut", time)
    points, cells = arrays(cut)
    expect(cut.GetDataInformation().GetNumberOfCells() > 0, f"{pvd}: the cut surface has cells at the last step")
    expect("opening" in points and "appears" in cells, f"{pvd}: cut arrays opening (points), appears (cells)")
    if grid:
        phi = block(reader, grid, time)
        expect("phi" in arrays(phi)[0] and phi.GetDataInformation().GetNumberOfPoints() > 1000,
               f"{pvd}: the grid's phi")


def check_pieces(mpi_pvd, serial_pvd):
    counts = []
    for pvd in (mpi_pvd, serial_pvd):
        reader = PVDReader(FileName=pvd)
        time = last_step(reader)
        reader.UpdatePipeline(time)
        data = servermanager.Fetch(reader)
        expect("displacement" in arrays(reader)[0], f"{pvd}: displacement")
        counts.append((data.GetNumberOfCells(), reader.GetDataInformation().GetNumberOfPoints()))
    expect(mpi_pvd.endswith(".pvd") and glob.glob(os.path.join(os.path.dirname(mpi_pvd), "*.pvtu")),
           f"{mpi_pvd}: a series of .pvtu")
    expect(counts[0][0] == counts[1][0], f"the .pvtu pieces hold every cell once: {counts[0][0]} == {counts[1][0]}")


def check_vti(vti):
    reader = OpenDataFile(vti)
    reader.UpdatePipeline()
    expect("phi" in arrays(reader)[0], f"{vti}: phi, read alone")


def check_picture(png):
    reader = PNGSeriesReader(FileNames=[png])
    reader.UpdatePipeline()
    image = servermanager.Fetch(reader)
    colours = image.GetPointData().GetScalars()
    distinct = {colours.GetTuple(i) for i in range(0, colours.GetNumberOfTuples(), 7)}
    expect(len(distinct) > 50, f"{png}: rendered ({len(distinct)} distinct colours)")


def main(cut_study, mpi_run, serial_run, out_dir):
    runs = os.path.join(cut_study, "runs")
    check_cut_series(os.path.join(runs, "nodal_grid", "cut.pvd"), body_cell_stress=False, grid="phi_cut0")
    check_cut_series(os.path.join(runs, "fem_remesh", "cut.pvd"), body_cell_stress=True, grid=None)
    check_cut_series(os.path.join(runs, "fem_split", "cut.pvd"), body_cell_stress=True, grid=None)
    check_vti(sorted(glob.glob(os.path.join(runs, "nodal_grid", "*_phi_*_0*.vti")))[-1])
    name = os.path.basename(glob.glob(os.path.join(serial_run, "*.pvd"))[0])
    check_pieces(os.path.join(mpi_run, name), os.path.join(serial_run, name))
    paraview_pictures.main(cut_study, out_dir, [400, 280])
    for way in ("fem_remesh", "fem_remove", "fem_split", "nodal_grid"):
        check_picture(os.path.join(out_dir, way + ".png"))
    if failures:
        sys.exit(f"{len(failures)} failed: " + "; ".join(failures))


main(*sys.argv[1:5])
