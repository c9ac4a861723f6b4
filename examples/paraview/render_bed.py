"""Renders a run's bed with ParaView (examples/paraview/README.md): the grains coloured by the stress
of their grid cell, the strong force chains as tubes, and the stress grid cut in half by a clip so
the grains show through the cut-away half. Run it with ParaView's batch interpreter:

  pvbatch render_bed.py OUTPUT_FOLDER [--field bagi_sigma_zz] [--time T] [--out PNG_OR_FOLDER]
                        [--size 800 620] [--check]

Off-screen: `pvbatch --force-offscreen-rendering render_bed.py ...` where ParaView was built with
EGL or OSMesa, otherwise under a virtual X server: `xvfb-run -a pvbatch render_bed.py ...`.

Reads particles.xdmf, grid_stress.xdmf and, when the run wrote it (Output/force network = true),
force_network.xdmf (docs/output.md), at the last time they share (or the one nearest to T):
- grains: sphere glyphs of the grain's radius (its major semi-axis for ellipsoids), coloured by
  --field of the grid cell holding the grain's centre (ResampleWithDataset from the grid's cell data);
- stress grid: the half with y below the middle, clipped away at y = the box's middle, drawn as a
  translucent surface coloured by the same field with its cell edges;
- force network: the contacts whose normal force exceeds 30 % of the range above its minimum, as
  tubes of a fifth of the largest grain radius coloured by normal_force_magnitude (reds); the
  grains are translucent (--grain-opacity) so the chains show through.
--check reads the PNG back and exits non-zero unless it exists and is not blank (at least 16
distinct colours and a spread of the pixel values)."""
import argparse
import os
import sys

from paraview.simple import (ColorBy, Clip, CreateView, ExtractSurface, Glyph, GetColorTransferFunction, GetScalarBar,
                             ResampleWithDataset, SaveScreenshot, Show, Threshold, Tube, UpdatePipeline,
                             Xdmf3ReaderS)


def last_shared_time(readers, time):
    """The time all readers have (their last common one), or the one nearest to `time`."""
    shared = set(readers[0].TimestepValues)
    for r in readers[1:]:
        shared &= {t for t in r.TimestepValues if min(abs(t - u) for u in shared) < 1e-9}
    if not shared:
        sys.exit("render_bed.py: the files share no time step")
    times = sorted(shared)
    return times[-1] if time is None else min(times, key=lambda t: abs(t - time))


def not_blank(path):
    """True when the PNG at path has some picture in it."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())
    colours = len({tuple(p) for p in pixels[::7][:, :3]})
    return colours >= 16 and pixels[:, :3].std() > 10, colours


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("folder")
    p.add_argument("--field", default="bagi_sigma_zz", help="a cell field of grid_stress.xdmf")
    p.add_argument("--time", type=float, default=None)
    p.add_argument("--out", default=None, help="the PNG, or a folder for bed.png (default: FOLDER/bed.png)")
    p.add_argument("--size", type=int, nargs=2, default=[800, 620])
    p.add_argument("--grain-opacity", type=float, default=0.3, help="below 1 the force chains show through")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    out = a.out or a.folder
    if not out.lower().endswith(".png"):
        os.makedirs(out, exist_ok=True)
        out = os.path.join(out, "bed.png")
    for name in ("particles.xdmf", "grid_stress.xdmf"):
        if not os.path.exists(os.path.join(a.folder, name)):
            sys.exit(f"render_bed.py: no {name} in {a.folder} (a run with Stress/formulas writes grid_stress.xdmf)")
    particles = Xdmf3ReaderS(FileName=[os.path.join(a.folder, "particles.xdmf")])
    grid = Xdmf3ReaderS(FileName=[os.path.join(a.folder, "grid_stress.xdmf")])
    network_file = os.path.join(a.folder, "force_network.xdmf")
    network = Xdmf3ReaderS(FileName=[network_file]) if os.path.exists(network_file) else None
    t = last_shared_time([particles, grid] + ([network] if network else []), a.time)
    UpdatePipeline(time=t, proxy=grid)
    if a.field not in grid.CellData.keys():
        sys.exit(f"render_bed.py: no cell field '{a.field}' in grid_stress.xdmf (it has: "
                 f"{', '.join(grid.CellData.keys())})")
    lo_field, hi_field = grid.CellData[a.field].GetRange()
    bounds = grid.GetDataInformation().GetBounds()
    middle = [(bounds[0] + bounds[1]) / 2, (bounds[2] + bounds[3]) / 2, (bounds[4] + bounds[5]) / 2]

    view = CreateView("RenderView")
    view.ViewSize = a.size
    view.ViewTime = t
    view.Background = [1, 1, 1]
    try:  # ParaView >= 5.10 draws the background from a palette unless told otherwise
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    view.OrientationAxesVisibility = 1

    # Grains: each takes the field of its cell (the grid's cell data probed at the grain's centre).
    probed = ResampleWithDataset(SourceDataArrays=grid, DestinationMesh=particles)
    probed.CellLocator = "Static Cell Locator"
    probed.PassPointArrays = 1  # keep the grains' radius for the glyphs
    glyphs = Glyph(Input=probed, GlyphType="Sphere")
    glyphs.ScaleArray = ["POINTS", "radius"]
    glyphs.ScaleFactor = 2.0  # the sphere source has radius 0.5
    glyphs.GlyphMode = "All Points"
    glyphs.GlyphType.ThetaResolution = 16
    glyphs.GlyphType.PhiResolution = 12
    shown = Show(glyphs, view)
    shown.Opacity = a.grain_opacity
    ColorBy(shown, ("POINTS", a.field))
    lut = GetColorTransferFunction(a.field)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.RescaleTransferFunction(lo_field, hi_field)
    shown.SetScalarBarVisibility(view, True)
    bar = GetScalarBar(lut, view)
    bar.Title = a.field + " (Pa)"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]

    # The stress grid with its front half (y below the middle) cut away.
    clip = Clip(Input=grid)
    clip.ClipType = "Plane"
    clip.ClipType.Origin = middle
    clip.ClipType.Normal = [0, 1, 0]
    clip.Invert = 0  # keep the half on the normal's side
    grid_shown = Show(clip, view)
    ColorBy(grid_shown, ("CELLS", a.field))
    grid_shown.Representation = "Surface With Edges"
    grid_shown.Opacity = 0.35

    if network is not None:
        UpdatePipeline(time=t, proxy=network)
        lo, hi = network.CellData["normal_force_magnitude"].GetRange()
        strong = Threshold(Input=network, Scalars=["CELLS", "normal_force_magnitude"])
        strong.LowerThreshold = lo + 0.3 * (hi - lo)
        strong.UpperThreshold = hi
        tubes = Tube(Input=ExtractSurface(Input=strong))  # Tube takes polygonal data
        UpdatePipeline(time=t, proxy=particles)
        tubes.Radius = 0.2 * particles.PointData["radius"].GetRange()[1]
        chains = Show(tubes, view)
        ColorBy(chains, ("CELLS", "normal_force_magnitude"))
        force_lut = GetColorTransferFunction("normal_force_magnitude")
        force_lut.ApplyPreset("Reds", True)
        force_lut.RescaleTransferFunction(lo, hi)

    view.CameraPosition = [middle[0] - 2.2 * (bounds[1] - bounds[0]), middle[1] - 2.8 * (bounds[3] - bounds[2]),
                           middle[2] + 1.6 * (bounds[5] - bounds[4])]
    view.CameraFocalPoint = middle
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    SaveScreenshot(out, view, ImageResolution=a.size)
    print(f"render_bed.py: {out} at t = {t:.4g} s, grains coloured by {a.field} "
          f"({lo_field:.1f} to {hi_field:.1f} Pa){', strong chains drawn' if network else ''}")
    if a.check:
        if not os.path.exists(out):
            sys.exit(f"check failed: {out} was not written")
        ok, colours = not_blank(out)
        if not ok:
            sys.exit(f"check failed: {out} is blank ({colours} colours)")
        print(f"check passed: {out} written, {colours} distinct colours")


if __name__ == "__main__":
    main()
