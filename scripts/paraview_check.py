"""Run by ``scripts/paraview-check.sh`` under ParaView's pvpython: open every .vtu and .pvd in
the folder given, print what ParaView read, and exit 1 when a file is empty or lacks flexlink's
ground and joint cells (cell data ``part``: 0 link, 1 ground, 2 joint spring, 3 joint), or when
the animation is not what Warp By Vector makes of the .vtu: frame 0 of ``<stem>_mode<n>.pvd``
must be ``<stem>.vtu`` warped by ``mode<n>_displacement`` times ``warp_scale``, and the frames
must hold no vector that a second Warp By Vector could add on top."""

import sys
from pathlib import Path

import numpy as np
from paraview import servermanager
from paraview.simple import OpenDataFile, WarpByVector
from vtk.util.numpy_support import vtk_to_numpy

# [m] round-off of positions written as float64 ASCII/binary and warped in double precision
WARP_TOLERANCE = 1e-12

folder = Path(sys.argv[1])
files = sorted(folder.glob("*.vtu")) + sorted(folder.glob("*.pvd"))
bad = [] if files else [f"no .vtu or .pvd in {folder}"]


def points(data) -> np.ndarray:
    return vtk_to_numpy(data.GetPoints().GetData())


def vectors(data) -> list[str]:
    arrays = data.GetPointData()
    return [arrays.GetArrayName(k) for k in range(arrays.GetNumberOfArrays())
            if arrays.GetArray(k).GetNumberOfComponents() == 3]


readers = {}
for path in files:
    reader = OpenDataFile(str(path))
    reader.UpdatePipeline()
    readers[path.name] = reader
    data = servermanager.Fetch(reader)
    part = data.GetCellData().GetArray("part")
    parts = sorted(set(vtk_to_numpy(part).tolist())) if part is not None else []
    fields = data.GetFieldData()
    joints = [fields.GetArrayName(k) for k in range(fields.GetNumberOfArrays())
              if fields.GetArrayName(k).startswith("joint_")]
    times = list(reader.TimestepValues) if path.suffix == ".pvd" else []
    print(f"{path.name}: {data.GetNumberOfPoints()} points, {data.GetNumberOfCells()} cells, "
          f"parts {parts}, joints {joints}" + (f", times {times[0]:.3g} ... {times[-1]:.3g}"
                                                if times else ""))
    if data.GetNumberOfCells() == 0 or not {0, 2, 3} <= set(parts) or not joints:
        bad.append(path.name)

vtus = [p for p in files if p.suffix == ".vtu"]
if len(vtus) == 1:
    grid = readers[vtus[0].name]
    rest = servermanager.Fetch(grid)
    scales = vtk_to_numpy(rest.GetFieldData().GetArray("warp_scale"))
    numbers = vtk_to_numpy(rest.GetFieldData().GetArray("mode_numbers")).tolist()
    for pvd in (p for p in files if p.suffix == ".pvd"):
        n = int(pvd.stem.rsplit("_mode", 1)[1])
        scale = float(scales[numbers.index(n)])
        warp = WarpByVector(Input=grid, Vectors=["POINTS", f"mode{n}_displacement"],
                            ScaleFactor=scale)
        warp.UpdatePipeline()
        warped = points(servermanager.Fetch(warp))
        frame = servermanager.Fetch(readers[pvd.name])  # time 0: the largest deflection
        gap = float(np.abs(points(frame) - warped).max())
        moved = float(np.linalg.norm(points(frame) - points(rest), axis=1).max())
        extra = vectors(frame)
        print(f"{pvd.name}: frame 0 = {vtus[0].name} warped by mode{n}_displacement x "
              f"{scale:.4g} to {gap:.1e} m (largest displacement {1e3 * moved:.2f} mm); "
              f"vector arrays in the frames: {extra or 'none'}")
        if gap > WARP_TOLERANCE or extra:
            bad.append(f"{pvd.name} (warp)")
if bad:
    print("paraview-check: FAILED: " + ", ".join(bad))
    sys.exit(1)
print(f"paraview-check: ParaView read all {len(files)} files")
