#!/usr/bin/env python3
"""Renders a STEP file as OpenCascade reads it, headless (VTK, EGL offscreen).

    render_step.py FILE.step OUT.png [WIDTH HEIGHT]

STEPControl_Reader reads the file; BRepMesh_IncrementalMesh triangulates each
face (deflection 2e-4 of the model size); the triangles are shaded grey and
every edge of the B-rep (the patch boundaries) is drawn as a dark line,
sampled at 16 points. The camera looks along (1, -2, 1.2) with z up.
"""

import sys

import vtk
from OCP.Bnd import Bnd_Box
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Curve
from OCP.BRepBndLib import BRepBndLib
from OCP.BRepMesh import BRepMesh_IncrementalMesh
from OCP.IFSelect import IFSelect_RetDone
from OCP.STEPControl import STEPControl_Reader
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_REVERSED
from OCP.TopExp import TopExp, TopExp_Explorer
from OCP.TopLoc import TopLoc_Location
from OCP.TopoDS import TopoDS
from OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as ShapeMap


def main():
    path, out = sys.argv[1], sys.argv[2]
    width, height = (int(sys.argv[3]), int(sys.argv[4])) if len(sys.argv) > 4 else (900, 700)
    reader = STEPControl_Reader()
    if reader.ReadFile(path) != IFSelect_RetDone:
        sys.exit(f"render_step: {path}: not read")
    reader.TransferRoots()
    shape = reader.OneShape()
    box = Bnd_Box()
    BRepBndLib.Add_s(shape, box)
    lo, hi = box.CornerMin(), box.CornerMax()
    x0, y0, z0, x1, y1, z1 = lo.X(), lo.Y(), lo.Z(), hi.X(), hi.Y(), hi.Z()
    size = max(x1 - x0, y1 - y0, z1 - z0)
    BRepMesh_IncrementalMesh(shape, 2e-4 * size, False, 0.2, True)

    points = vtk.vtkPoints()
    tris = vtk.vtkCellArray()
    ex = TopExp_Explorer(shape, TopAbs_FACE)
    while ex.More():
        face = TopoDS.Face(ex.Current())
        loc = TopLoc_Location()
        t = BRep_Tool.Triangulation_s(face, loc)
        if t is not None:
            trsf = loc.Transformation()
            base = points.GetNumberOfPoints()
            for k in range(1, t.NbNodes() + 1):
                p = t.Node(k).Transformed(trsf)
                points.InsertNextPoint(p.X(), p.Y(), p.Z())
            flip = face.Orientation() == TopAbs_REVERSED
            for k in range(1, t.NbTriangles() + 1):
                a, b, c = t.Triangle(k).Get()
                if flip:
                    b, c = c, b
                tris.InsertNextCell(3, [base + a - 1, base + b - 1, base + c - 1])
        ex.Next()
    surface = vtk.vtkPolyData()
    surface.SetPoints(points)
    surface.SetPolys(tris)
    normals = vtk.vtkPolyDataNormals()
    normals.SetInputData(surface)
    normals.SetFeatureAngle(60)
    normals.ConsistencyOff()
    normals.AutoOrientNormalsOff()
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(normals.GetOutputPort())
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(0.80, 0.80, 0.84)
    actor.GetProperty().SetSpecular(0.3)
    actor.GetProperty().SetSpecularPower(30)
    # Push the surface back a little so the edge lines on it stay visible.
    mapper.SetResolveCoincidentTopologyToPolygonOffset()

    edges = ShapeMap()
    TopExp.MapShapes_s(shape, TopAbs_EDGE, edges)
    lp = vtk.vtkPoints()
    lines = vtk.vtkCellArray()
    for k in range(1, edges.Extent() + 1):
        e = TopoDS.Edge(edges.FindKey(k))
        if BRep_Tool.Degenerated_s(e):
            continue
        c = BRepAdaptor_Curve(e)
        a, b = c.FirstParameter(), c.LastParameter()
        ids = []
        for i in range(17):
            p = c.Value(a + (b - a) * i / 16)
            ids.append(lp.InsertNextPoint(p.X(), p.Y(), p.Z()))
        lines.InsertNextCell(len(ids), ids)
    wire = vtk.vtkPolyData()
    wire.SetPoints(lp)
    wire.SetLines(lines)
    wmapper = vtk.vtkPolyDataMapper()
    wmapper.SetInputData(wire)
    wactor = vtk.vtkActor()
    wactor.SetMapper(wmapper)
    wactor.GetProperty().SetColor(0.15, 0.2, 0.35)
    wactor.GetProperty().SetLineWidth(1.0)
    wactor.GetProperty().LightingOff()

    ren = vtk.vtkRenderer()
    ren.SetBackground(1, 1, 1)
    ren.AddActor(actor)
    ren.AddActor(wactor)
    cam = ren.GetActiveCamera()
    cx, cy, cz = (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2
    cam.SetFocalPoint(cx, cy, cz)
    cam.SetPosition(cx + size, cy - 2 * size, cz + 1.2 * size)
    cam.SetViewUp(0, 0, 1)
    ren.ResetCamera()
    cam.Zoom(1.45)
    win = vtk.vtkRenderWindow()
    win.SetOffScreenRendering(1)
    win.SetSize(width, height)
    win.SetMultiSamples(8)
    win.AddRenderer(ren)
    win.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.Update()
    png = vtk.vtkPNGWriter()
    png.SetFileName(out)
    png.SetInputConnection(grab.GetOutputPort())
    png.Write()
    print(f"render_step: {out}: {tris.GetNumberOfCells()} triangles, {lines.GetNumberOfCells()} edges")


if __name__ == "__main__":
    main()
