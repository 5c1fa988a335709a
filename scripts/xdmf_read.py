#!/usr/bin/env python3
"""Read a case folder's results.xmf with one of ParaView's XDMF readers and
save what it read, for scripts/test_xdmf.sh to compare with results.h5.

usage: xdmf_read.py READER CASE_FOLDER OUT.npz
  READER  vtkXdmfReader   VTK's legacy XDMF reader (the `vtk` wheel, or ParaView's VTK)
          vtkXdmf3Reader  VTK's XDMF3 reader (in ParaView's VTK; not in the `vtk` wheel)
          XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT
                          ParaView's reader proxies (paraview.simple; the readers its
                          File > Open offers for .xmf): run under pvpython
Every time step the reader reports is read, and the point set warped by the
nodal `displacement` (vtkWarpVector, ParaView's Warp By Vector, scale 1).
OUT.npz holds, per step k: time_k, points_k, cells_k (connectivity),
types_k (VTK cell types), warped_k, and point_<name>_k / cell_<name>_k for
every array read. Only numpy is needed beside VTK or ParaView (h5py is not:
ParaView's Python may lack it). Exit 2: READER cannot be had here.
"""
import os
import sys

import numpy as np


def flatten(data):
    """A copy of the one dataset of a pipeline's output (a multiblock of one block, or the
    dataset itself): the next update may reuse the output's memory (ParaView's Fetch does)."""
    while data is not None and not data.IsA("vtkDataSet"):
        if data.IsA("vtkMultiBlockDataSet") and data.GetNumberOfBlocks() == 1:
            data = data.GetBlock(0)
        elif data.IsA("vtkPartitionedDataSet") and data.GetNumberOfPartitions() == 1:
            data = data.GetPartition(0)
        else:
            raise SystemExit(f"xdmf_read: the reader gave a {data.GetClassName()}, not one dataset")
    copy = data.NewInstance()
    copy.DeepCopy(data)
    return copy


def arrays(prefix, attributes, k, to_numpy, out):
    for i in range(attributes.GetNumberOfArrays()):
        array = attributes.GetArray(i)
        values = to_numpy(array)
        if array.GetNumberOfComponents() > 1:
            values = values.reshape(array.GetNumberOfTuples(), array.GetNumberOfComponents())
        out[f"{prefix}_{attributes.GetArrayName(i)}_{k}"] = values


def save(grid, warped, k, time, to_numpy, out):
    out[f"time_{k}"] = np.array(time)
    out[f"points_{k}"] = to_numpy(grid.GetPoints().GetData()).copy()
    cells = grid.GetCells()
    out[f"cells_{k}"] = to_numpy(cells.GetConnectivityArray()).copy()
    out[f"offsets_{k}"] = to_numpy(cells.GetOffsetsArray()).copy()
    out[f"types_{k}"] = np.array([grid.GetCellType(i) for i in range(grid.GetNumberOfCells())])
    arrays("point", grid.GetPointData(), k, to_numpy, out)
    arrays("cell", grid.GetCellData(), k, to_numpy, out)
    out[f"warped_{k}"] = to_numpy(warped.GetPoints().GetData()).copy()


def read_vtk(kind, path, out):
    try:
        from vtkmodules.util.numpy_support import vtk_to_numpy
        from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
        from vtkmodules.vtkFiltersGeneral import vtkWarpVector
        if kind == "vtkXdmfReader":
            from vtkmodules.vtkIOXdmf2 import vtkXdmfReader as reader_class
        else:
            from vtkmodules.vtkIOXdmf3 import vtkXdmf3Reader as reader_class
    except ImportError as error:
        print(f"xdmf_read: no {kind} here ({error})", file=sys.stderr)
        raise SystemExit(2)
    reader = reader_class()
    reader.SetFileName(path)
    reader.UpdateInformation()
    steps = reader.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS()) or (0.0,)
    warp = vtkWarpVector()
    warp.SetInputConnection(reader.GetOutputPort())
    warp.SetInputArrayToProcess(0, 0, 0, 0, "displacement")   # 0: vtkDataObject::FIELD_ASSOCIATION_POINTS
    warp.SetScaleFactor(1.0)
    for k, time in enumerate(steps):
        reader.UpdateTimeStep(time)
        grid = flatten(reader.GetOutputDataObject(0))
        warp.UpdateTimeStep(time)
        save(grid, flatten(warp.GetOutputDataObject(0)), k, time, vtk_to_numpy, out)
    out["steps_reported"] = np.array(len(reader.GetOutputInformation(0).Get(
        vtkStreamingDemandDrivenPipeline.TIME_STEPS()) or ()))


def read_paraview(kind, path, out):
    try:
        from paraview import simple, servermanager
        from vtkmodules.util.numpy_support import vtk_to_numpy
    except ImportError as error:
        print(f"xdmf_read: no ParaView here for {kind} ({error})", file=sys.stderr)
        raise SystemExit(2)
    if kind == "XDMFReader":
        reader = simple.XDMFReader(FileNames=[path])
    else:
        reader = getattr(simple, kind)(FileName=[path])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    warp = simple.WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=1.0)
    for k, time in enumerate(times or [0.0]):
        reader.UpdatePipeline(time)
        grid = flatten(servermanager.Fetch(reader))
        warp.UpdatePipeline(time)
        save(grid, flatten(servermanager.Fetch(warp)), k, time, vtk_to_numpy, out)
    out["steps_reported"] = np.array(len(times))


def main():
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    kind, folder, npz = sys.argv[1:]
    # absolute: given a relative name, the XDMF3 reader of ParaView 5.11 did
    # not find results.h5 (it looked for "<name>results.h5")
    path = os.path.abspath(os.path.join(folder, "results.xmf"))
    out = {}
    if kind in ("vtkXdmfReader", "vtkXdmf3Reader"):
        read_vtk(kind, path, out)
    elif kind in ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT"):
        read_paraview(kind, path, out)
    else:
        raise SystemExit(f"xdmf_read: unknown reader {kind}\n{__doc__}")
    try:
        from vtkmodules.vtkCommonCore import vtkVersion
        out["vtk_version"] = np.array(vtkVersion.GetVTKVersion())
    except ImportError:
        pass
    np.savez(npz, **out)


if __name__ == "__main__":
    main()
