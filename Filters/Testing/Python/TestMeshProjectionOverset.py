"""A Source of two overlapping layers that share no point (overset blocks in
one unstructured grid, the second stored clockwise), and an Input of
separate small triangles (no shared points) inside the overlap, away from
either layer's boundary, in random order (VTK Python: /usr/bin/python3 with
the build's python directory on PYTHONPATH).

Each Input triangle starts a front of its own; once walks toward them run
out of their budget, a triangle that meets no boundary cell nearby is
settled by the ray test (CandidateLocator::Outside) or by a query among all
Source cells. Inside both layers the ray crosses the boundary faces an even
number of times: a parity would call the triangle outside, its values
invalid and the overlap unsaid. Checked, on one thread and on every core:
 - every point valid, the linear field exact, the warning "covered more
   than once";
 - the values equal those of the same pair tilted out of the plane z = 0
   (seen in a plane frame, where the ray test is not used: the query among
   all cells decides), to 1e-12 of the range;
 - each triangle takes a field that differs between the layers (0 on the
   first, 1 on the second) from the first layer alone, the second alone,
   or both (the brute-force search's value), each computed independently;
   some from both (the query among all cells found them), and on one
   thread every triangle after the first such one (no walks after it).
"""
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonDataModel import VTK_TRIANGLE

from mpsupport import meshes
from mpsupport.testing import check, finish, observed_filter

M = 60  # cells per side of each layer
TRIANGLES = 3000  # Input triangles


def linear(x):
    return 1.0 + 2.0 * x[:, 0] - 3.0 * x[:, 1]


def source_grid(layers, rotation):
    """One grid of the layers ((points, triangles, value of g) each), points
    not merged, rotated by `rotation`; point arrays f (linear) and g."""
    x = np.concatenate([p for p, _, _ in layers])
    offsets = np.cumsum([0] + [len(p) for p, _, _ in layers])
    cells = np.concatenate([t + o for (_, t, _), o in zip(layers, offsets)])
    grid = meshes.grid(x @ rotation.T, cells, VTK_TRIANGLE)
    meshes.add_array(grid.GetPointData(), "f", linear(x))
    meshes.add_array(grid.GetPointData(), "g", np.concatenate([np.full(len(p), v) for p, _, v in layers]))
    return grid


def project(target, source, threads=0, brute=False):
    f, said = observed_filter("WarningEvent")
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetCacheOperator(False)
    f.SetNumberOfThreads(threads)
    # In the Input's own order, whatever the renumbered test pass sets as the
    # default: renumbered along space, the walks reach every triangle within
    # their budget (from the layer they start in), and the ray test this
    # checks is never asked.
    f.SetRenumbering(f.NEVER_RENUMBER)
    if brute:
        f.SetSearchMethodToBruteForce()
    f.Update()
    return f.GetOutput(), said


def values(out, name):
    """Point array `name` per Input triangle (3 values: its own points)."""
    return vtk_to_numpy(out.GetPointData().GetArray(name)).reshape(-1, 3)


first = meshes.triangles(M, (0.0, 0.0), (1.0, 1.0), 1)
second_points, second = meshes.triangles(M, (0.4, 0.0), (1.4, 1.0), 2)
second = (second_points, second[:, ::-1])  # clockwise
layers = [first + (0.0,), second + (1.0,)]
flat = np.eye(3)
tilt = 0.7
tilted = np.array([[1, 0, 0], [0, np.cos(tilt), -np.sin(tilt)], [0, np.sin(tilt), np.cos(tilt)]])

# Input: small separate triangles, centres at random in the overlap, three
# cells away from either layer's boundary (no boundary cell's box reaches).
rng = np.random.default_rng(3)
margin = 3.0 / M
centres = np.stack([rng.uniform(0.4 + margin, 1.0 - margin, TRIANGLES),
                    rng.uniform(margin, 1.0 - margin, TRIANGLES)], 1)
h = 0.3 / M
corners = np.zeros((3 * TRIANGLES, 3))
corners[:, :2] = (centres[:, None, :] + np.array([[-h, -h], [h, -h], [0.0, h]])[None]).reshape(-1, 2)
cells = np.arange(3 * TRIANGLES).reshape(-1, 3)


def target_grid(rotation):
    return meshes.grid(corners @ rotation.T, cells, VTK_TRIANGLE)


# Independent values per triangle: each layer alone, both (brute force).
alone = [values(project(target_grid(flat), source_grid([layer], flat), brute=True)[0], "g")
         for layer in layers]
both, said = project(target_grid(flat), source_grid(layers, flat), brute=True)
both = values(both, "g")
check(np.allclose(alone[0], 0.0, atol=1e-12) and np.allclose(alone[1], 1.0, atol=1e-12)
      and np.allclose(both, 0.5, atol=1e-12), "the layers' g apart, both averaged by the brute force")
check(any("covered more than once" in s for s in said), "brute force: the overlap said")

for threads in (1, 0):
    what = "one thread" if threads == 1 else "every core"
    out, said = project(target_grid(flat), source_grid(layers, flat), threads)
    valid = vtk_to_numpy(out.GetPointData().GetArray("vtkValidPointMask"))
    check(valid.all(), "%s: every point valid (%d not)" % (what, np.sum(valid == 0)))
    check(any("covered more than once" in s for s in said), "%s: the overlap said (%s)" % (what, said))
    f = vtk_to_numpy(out.GetPointData().GetArray("f"))
    error = np.max(np.abs(f - linear(corners)))
    check(error <= 1e-12, "%s: linear exact (%.2g off)" % (what, error))
    g = values(out, "g")
    # The same pair out of the plane z = 0: the query among all cells decides.
    reference = values(project(target_grid(tilted), source_grid(layers, tilted), threads)[0], "g")
    off = np.nanmax(np.abs(g - reference)) if np.isfinite(g).all() else np.inf
    print("%s: largest difference to the tilted pair %.3g" % (what, off))
    check(off <= 1e-12, "%s: the tilted pair's values (%.2g off)" % (what, off))
    near = [np.all(np.abs(g - v) <= 1e-12, axis=1) for v in (alone[0], alone[1], both)]
    check(np.all(near[0] | near[1] | near[2]), "%s: every triangle from one layer or both (%d not)"
          % (what, np.sum(~(near[0] | near[1] | near[2]))))
    doubled = np.flatnonzero(near[2])
    print("%s: %d triangles from the first layer, %d from the second, %d from both"
          % (what, near[0].sum(), near[1].sum(), near[2].sum()))
    check(doubled.size > 0, "%s: some triangles from both layers" % what)
    if threads == 1 and doubled.size:
        check(near[2][doubled[0]:].all(), "one thread: every triangle from both after the first")

finish()
