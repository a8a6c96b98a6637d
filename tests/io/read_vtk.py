"""Read a .vtu or .vtm with VTK's own XML readers (Debian's python3-vtk9) and print what
tests/io/test_vtk_xml.cpp checks, one fact a line:
  dataset <name> <kind> <points> <cells>      a block (the .vtu alone: name "volume")
  types <code>...                             the volume's VTK cell types, in cell order
  array <name> <values>...                    each cell-data array of the volume, %.17g
  inward <count>                              the volume's cell faces whose normal (VTK's face
                                              order) points into their cell: 0 if the node
                                              order is VTK's
  field <block> <name> <value>                each string field-data array of a patch block
  patchcells <block> <values>...              a patch block's `patch` cell data
Exit status 2 if VTK cannot read the file (an error message from VTK on stderr)."""
import sys

import vtk


def read(path):
    reader = vtk.vtkXMLMultiBlockDataReader() if path.endswith(".vtm") else vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    failed = []
    reader.AddObserver("ErrorEvent", lambda *_: failed.append(1))
    reader.Update()
    if failed or reader.GetErrorCode():
        sys.exit(2)
    return reader.GetOutput()


def centroid(points, ids):
    c = [0.0, 0.0, 0.0]
    for i in ids:
        p = points.GetPoint(i)
        for k in range(3):
            c[k] += p[k] / len(ids)
    return c


def inward_faces(grid):
    """Faces whose Newell normal points towards their cell's centroid."""
    count = 0
    points = grid.GetPoints()
    for c in range(grid.GetNumberOfCells()):
        cell = grid.GetCell(c)
        ids = [cell.GetPointId(i) for i in range(cell.GetNumberOfPoints())]
        cc = centroid(points, ids)
        for f in range(cell.GetNumberOfFaces()):
            face = cell.GetFace(f)
            fids = [face.GetPointId(i) for i in range(face.GetNumberOfPoints())]
            n = [0.0, 0.0, 0.0]
            for i, a in enumerate(fids):
                p, q = points.GetPoint(a), points.GetPoint(fids[(i + 1) % len(fids)])
                n[0] += (p[1] - q[1]) * (p[2] + q[2])
                n[1] += (p[2] - q[2]) * (p[0] + q[0])
                n[2] += (p[0] - q[0]) * (p[1] + q[1])
            fc = centroid(points, fids)
            if sum(n[k] * (fc[k] - cc[k]) for k in range(3)) <= 0.0:
                count += 1
    return count


def volume(name, grid):
    print("dataset", name, grid.GetClassName(), grid.GetNumberOfPoints(), grid.GetNumberOfCells(), sep="\t")
    print("types", *[grid.GetCellType(c) for c in range(grid.GetNumberOfCells())], sep="\t")
    data = grid.GetCellData()
    for a in range(data.GetNumberOfArrays()):
        arr = data.GetArray(a)
        print("array", arr.GetName(), *["%.17g" % arr.GetValue(i) for i in range(arr.GetNumberOfTuples())], sep="\t")
    print("inward", inward_faces(grid), sep="\t")


def patch(name, poly):
    print("dataset", name, poly.GetClassName(), poly.GetNumberOfPoints(), poly.GetNumberOfCells(), sep="\t")
    fields = poly.GetFieldData()
    for a in range(fields.GetNumberOfArrays()):
        arr = fields.GetAbstractArray(a)
        print("field", name, arr.GetName(), arr.GetValue(0), sep="\t")
    cells = poly.GetCellData().GetArray("patch")
    print("patchcells", name, *[cells.GetValue(i) for i in range(cells.GetNumberOfTuples())], sep="\t")


def main(path):
    out = read(path)
    if not path.endswith(".vtm"):
        volume("volume", out)
        return
    for b in range(out.GetNumberOfBlocks()):
        name = out.GetMetaData(b).Get(vtk.vtkCompositeDataSet.NAME())
        block = out.GetBlock(b)
        if block.IsA("vtkMultiBlockDataSet"):
            for p in range(block.GetNumberOfBlocks()):
                patch(block.GetMetaData(p).Get(vtk.vtkCompositeDataSet.NAME()), block.GetBlock(p))
        else:
            volume(name, block)


if __name__ == "__main__":
    main(sys.argv[1])
