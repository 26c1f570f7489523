"""Opens a run's particles.xmf as a ParaView user would (File > Open, the reader ParaView picks,
the default view) and checks that the particles are there to see: run by pvpython from
check_particles_in_paraview.sh on the run of coated-particles.yaml.

Asserted, against the scene and a hand calculation (see coated-particles.yaml):
  - the reader makes one cell per particle (a Polyvertex each), not points only;
  - the time steps are the run's snapshot times;
  - at t = 0.01 s each particle's id, position and coating_mass (1.1309734e-11 kg in the zone,
    0 outside) are those of the scene;
  - the default representation (Surface) in the default render view draws pixels.
"""
import sys

from paraview import simple

xmf = sys.argv[1]
image = sys.argv[2]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


reader = simple.OpenDataFile(xmf)
check(reader is not None, "ParaView opens " + xmf)
if reader is None:
    sys.exit(1)
print("reader:", reader.GetXMLName())

times = list(reader.TimestepValues)
check(len(times) == 6 and all(abs(t - 0.002 * i) < 1e-12 for i, t in enumerate(times)),
      "time steps are the snapshots 0, 0.002, ..., 0.01 s: %s" % times)

reader.UpdatePipeline(times[-1])
data = simple.servermanager.Fetch(reader)
while data.IsA("vtkMultiBlockDataSet"):
    data = data.GetBlock(0)
points, cells = data.GetNumberOfPoints(), data.GetNumberOfCells()
check(points == 5, "5 particles: %d points" % points)
check(cells == points, "one cell per particle: %d cells for %d points" % (cells, points))

ids = data.GetPointData().GetArray("id")
coating = data.GetPointData().GetArray("coating_mass")
check(ids is not None, "point array 'id' present")
check(coating is not None, "point array 'coating_mass' present")
if ids is not None and coating is not None:
    per_particle = 10 * 2 * 3.141592653589793 * 1.8e-5 * 1e-3 * 0.01 * 1e-3  # 1.1309734e-11 kg
    scene = {1: (0, 0, 0), 2: (0.01, 0, 0.2), 3: (0, 0.01, 0.4), 4: (0, 0, 0.7),
             5: (0.02, 0.02, 1)}
    seen = set()
    for i in range(points):
        pid = int(ids.GetValue(i))
        seen.add(pid)
        x = data.GetPoint(i)
        check(pid in scene and max(abs(a - b) for a, b in zip(x, scene[pid])) < 1e-15,
              "particle %d at %s" % (pid, x))
        expected = per_particle if scene.get(pid, (0, 0, 1))[2] < 0.5 else 0.0
        value = coating.GetValue(i)
        check(abs(value - expected) <= 1e-12 * per_particle,
              "particle %d coating_mass %.9g kg (expected %.9g)" % (pid, value, expected))
    check(seen == set(scene), "ids %s" % sorted(seen))

# The default view: Show() with nothing changed draws the particles (Surface of their cells).
view = simple.GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
shown = simple.Show(reader, view)
check(shown.Representation == "Surface", "default representation: %s" % shown.Representation)
view.ViewTime = times[-1]
simple.ResetCamera(view)
simple.Render(view)
simple.SaveScreenshot(image, view, ImageResolution=[300, 300])

from vtkmodules.vtkIOImage import vtkPNGReader  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

png = vtkPNGReader()
png.SetFileName(image)
png.Update()
pixels = vtk_to_numpy(png.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
background = pixels[0]
drawn = int((abs(pixels - background).sum(axis=1) > 30).sum())
check(drawn >= 5, "the default view draws the particles: %d pixels differ from the background"
      % drawn)

if failures:
    print("%d check(s) failed" % len(failures))
    sys.exit(1)
print("all checks passed")
