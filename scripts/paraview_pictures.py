"""Pictures of a cut body at its last step, through ParaView itself (pvbatch):
the body warped by its displacement and coloured by von Mises, the cut
surface drawn over it. One PNG per run of a cut study.

    scripts/pvbatch.sh scripts/paraview_pictures.py STUDY_DIR OUT_DIR [WIDTH HEIGHT]

STUDY_DIR holds runs/<way>/cut.pvd (`kerf study cut`); writes OUT_DIR/<way>.png.
"""
import os
import re
import sys

from paraview.simple import (ColorBy, CreateView, ExtractBlock, GetAnimationScene, GetColorTransferFunction,
                             GetScalarBar, MergeBlocks, PVDReader, Render, SaveScreenshot, Show, WarpByVector)


def part_names(pvd):
    """The parts the collection lists (kerf names them: body, cut, phi_...)."""
    with open(pvd) as f:
        return set(re.findall(r'name="([^"]+)"', f.read()))


def render_last_step(pvd, png, size):
    parts = part_names(pvd)
    reader = PVDReader(FileName=pvd)
    reader.UpdatePipelineInformation()
    last = reader.TimestepValues[-1] if reader.TimestepValues else 0.0
    GetAnimationScene().AnimationTime = last
    view = CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [1.0, 1.0, 1.0]
    # One part is read as the body itself; several as blocks named after them.
    body = reader if len(parts) < 2 else MergeBlocks(Input=ExtractBlock(Input=reader, Selectors=["/Root/body"]))
    body = WarpByVector(Input=body, Vectors=["POINTS", "displacement"])
    shown = Show(body, view)
    body.UpdatePipeline(last)
    ColorBy(shown, ("CELLS" if "von_mises" in body.CellData.keys() else "POINTS", "von_mises"))  # FEM: per cell
    shown.RescaleTransferFunctionToDataRange(True)
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(GetColorTransferFunction("von_mises"), view)
    bar.Title, bar.ComponentTitle = "von Mises (Pa)", ""
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]  # the palette's white on a white background
    if body.GetDataInformation().GetNumberOfCells() == body.GetDataInformation().GetNumberOfPoints():
        shown.SetRepresentationType("Points")  # a meshless body: its nodes
        shown.PointSize = 5
        shown.RenderPointsAsSpheres = 1
    if "cut" in parts:
        cut = Show(MergeBlocks(Input=ExtractBlock(Input=reader, Selectors=["/Root/cut"])), view)
        cut.DiffuseColor = [0.15, 0.15, 0.15]
        cut.AmbientColor = [0.15, 0.15, 0.15]
    view.CameraPosition = [1.0, -1.6, 0.9]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    Render(view)
    SaveScreenshot(png, view, ImageResolution=size)


def main(study_dir, out_dir, size):
    os.makedirs(out_dir, exist_ok=True)
    runs = os.path.join(study_dir, "runs")
    for way in sorted(os.listdir(runs)):
        pvd = os.path.join(runs, way, "cut.pvd")
        if os.path.exists(pvd):
            render_last_step(pvd, os.path.join(out_dir, way + ".png"), size)
            print(os.path.join(out_dir, way + ".png"))


if __name__ == "__main__":
    size = [int(sys.argv[3]), int(sys.argv[4])] if len(sys.argv) > 4 else [400, 280]
    main(sys.argv[1], sys.argv[2], size)
