"""End-to-end VTK: the reader for the format + vtkMassProperties, as JSON.

Run as a fresh process by compare.py; the whole process is what gets timed. vtkSTLReader
merges coincident points (its default). vtkMassProperties needs triangles and does not
check that the surface is closed; errors it reports (through VTK's output window) are
printed as {"refused": reason}.
"""
import json
import sys

from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkFiltersCore import vtkMassProperties
from vtkmodules.vtkIOGeometry import vtkOBJReader, vtkSTLReader
from vtkmodules.vtkIOPLY import vtkPLYReader

messages = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(messages)
path = sys.argv[1]
ext = path.rsplit(".", 1)[-1].lower()
reader = {"stl": vtkSTLReader, "ply": vtkPLYReader, "obj": vtkOBJReader}[ext]()
reader.SetFileName(path)
mp = vtkMassProperties()
mp.SetInputConnection(reader.GetOutputPort())
mp.Update()
volume = mp.GetVolume()
poly = reader.GetOutput()
text = messages.GetOutput()
if "ERROR" in text or poly.GetNumberOfCells() == 0:
    line = next((ln for ln in text.splitlines() if ln.strip() and "ERROR" not in ln), text.strip())
    print(json.dumps({"refused": line.strip()[:200] or "no cells read"}))
    sys.exit(0)
print(json.dumps({
    "volume": float(volume),
    "area": float(mp.GetSurfaceArea()),
    "volume_projected": float(mp.GetVolumeProjected()),
    "triangles": int(poly.GetNumberOfCells()),
    "vertices": int(poly.GetNumberOfPoints()),
}))
