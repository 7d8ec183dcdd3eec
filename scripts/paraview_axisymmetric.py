#!/usr/bin/env pvpython
"""Shows an axisymmetric Krug run in ParaView as the whole body: mirrored about the axis (a full
section) or swept about the axis (3D). Krug writes axisymmetric results as the (z, r) half plane:
points (z, r, 0), the symmetry axis along the file's x axis (docs/outputs.md).

  pvpython paraview_axisymmetric.py OUT/run.pvd                 # mirrored section, interactive
  pvpython paraview_axisymmetric.py OUT/run.pvd --sweep 270     # 3D, a 270-degree sweep (cut open)
  pvpython paraview_axisymmetric.py OUT/final.vtu --field von_mises_stress --png view.png

In the ParaView GUI the same by hand:
  mirrored: Filters > Reflect, Plane "Y", Center 0, Copy Input on.
  3D: Filters > Extract Surface; Filters > Transform, Rotate (0, -90, 0), which turns the axis (file x)
  into ParaView's Z axis; Filters > Rotational Extrusion, Angle 270 (or 360), Resolution 72, Capping on.
The sweep is a picture only: the swept cells are surfaces, so do not integrate over them; Krug's own
ledgers (summary.json, history.csv) hold the whole body's mass, momentum and energy.
Written against the paraview.simple interface (ParaView 5.9 and later).
"""
import argparse

from paraview.simple import (ColorBy, ExtractSurface, GetActiveViewOrCreate, GetAnimationScene, Interact,
                             OpenDataFile, Reflect, RotationalExtrusion, SaveScreenshot, Show, Transform)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("file", help="run.pvd, final.vtu or a snapshot .vtu of an axisymmetric run")
    parser.add_argument("--field", default="equivalent_plastic_strain", help="cell field to colour by")
    parser.add_argument("--sweep", type=float, default=0.0,
                        help="sweep angle in degrees for a 3D view (0: the mirrored section instead)")
    parser.add_argument("--png", help="save a picture of the last time step instead of opening a window")
    args = parser.parse_args()

    source = OpenDataFile(args.file)
    GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
    if args.sweep > 0.0:
        surface = ExtractSurface(Input=source)
        # The axis (file x) becomes ParaView's Z axis, the axis the extrusion turns about:
        # a rotation of -90 degrees about y maps (z, r, 0) to (0, r, z).
        upright = Transform(Input=surface)
        upright.Transform.Rotate = [0.0, -90.0, 0.0]
        shown = RotationalExtrusion(Input=upright)
        shown.Angle = args.sweep
        shown.Resolution = max(4, int(args.sweep / 5.0))
        shown.Capping = 1
    else:
        shown = Reflect(Input=source)
        shown.Plane = "Y"
        shown.Center = 0.0
        shown.CopyInput = 1

    view = GetActiveViewOrCreate("RenderView")
    display = Show(shown, view)
    ColorBy(display, ("CELLS", args.field))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    view.ResetCamera()
    if args.png:
        scene = GetAnimationScene()
        scene.AnimationTime = scene.EndTime
        SaveScreenshot(args.png, view, ImageResolution=[1600, 900])
    else:
        Interact(view)


if __name__ == "__main__":
    main()
