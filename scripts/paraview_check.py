"""Run by ``scripts/paraview-check.sh`` under ParaView's pvbatch: open every .vtu and .pvd in
the folder given, print what ParaView read, exit 1 when a file is empty or lacks flexlink's
ground and joint cells (cell data ``part``: 0 link, 1 ground, 2 joint spring, 3 joint)."""

import sys
from pathlib import Path

from paraview import servermanager
from paraview.simple import OpenDataFile
from vtk.util.numpy_support import vtk_to_numpy

folder = Path(sys.argv[1])
files = sorted(folder.glob("*.vtu")) + sorted(folder.glob("*.pvd"))
bad = [] if files else [f"no .vtu or .pvd in {folder}"]
for path in files:
    reader = OpenDataFile(str(path))
    reader.UpdatePipeline()
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
if bad:
    print("paraview-check: FAILED: " + ", ".join(bad))
    sys.exit(1)
print(f"paraview-check: ParaView read all {len(files)} files")
