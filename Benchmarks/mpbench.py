"""What the benchmark scripts share: the filter timed on a pair, as docs/performance.md
reports it, and the jittered pairs of the unit square and cube (the meshes of
mpsupport.meshes, shared with the tests) as numpy arrays and VTK grids."""
import re
import subprocess
import time

import numpy as np
from mpsupport import meshes
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE

UNIT = ((0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


def square_mesh(nx, ny, seed):
    """Triangles of a jittered nx x ny grid of the unit square: (points, cells, type)."""
    return (*meshes.triangles((nx, ny), *UNIT, seed, jitter=0.25), VTK_TRIANGLE)


def cube_mesh(nx, ny, nz, seed):
    """Tetrahedra (six per cube, conforming) of a jittered nx x ny x nz grid
    of the unit cube: (points, cells, type). Less jitter than the square's:
    tetrahedra invert sooner."""
    return (*meshes.tetrahedra((nx, ny, nz), *UNIT, seed, jitter=0.15), VTK_TETRA)


def to_grid(points, cells, cell_type, field=None):
    """A vtkUnstructuredGrid wrapping the points' numpy buffer (not copied),
    with `field` as the point array "u"."""
    grid = meshes.grid(points, cells, cell_type, deep=False)
    if field is not None:
        u = numpy_to_vtk(np.ascontiguousarray(field), deep=1)
        u.SetName("u")
        grid.GetPointData().AddArray(u)
    return grid


def shifted_pair(dim, cells):
    """A target of about `cells` cells (the jittered square's triangles or
    the cube's tetrahedra) and a Source of about 0.8 times as many on the
    box shifted a little: (target, source) as (points, cells, type)."""
    if dim == 2:
        n = max(2, int(round(np.sqrt(cells / 2.0))))
        m = max(2, int(round(np.sqrt(0.8 * cells / 2.0))))
        t, s = square_mesh(n, n, 1), square_mesh(m, m, 2)
    else:
        n = max(2, int(round((cells / 6.0) ** (1.0 / 3))))
        m = max(2, int(round((0.8 * cells / 6.0) ** (1.0 / 3))))
        t, s = cube_mesh(n, n, n, 1), cube_mesh(m, m, m, 2)
    shifted = (s[0] + np.array([0.013, -0.011, 0.007 if dim == 3 else 0.0]), s[1], s[2])
    return t, shifted


def shuffled(mesh, seed):
    """The same (points, cells, kind) mesh with its points and cells numbered at random."""
    points, cells, kind = mesh
    rng = np.random.default_rng(seed)
    order = rng.permutation(len(points))
    new_id = np.empty_like(order)
    new_id[order] = np.arange(len(order))
    return points[order], new_id[cells][rng.permutation(len(cells))], kind


def timed_run(target, source, threads, **properties):
    """One fresh run of the filter on `threads` threads (CacheOperator off:
    search, assembly and solve each run), with any other property by name
    (CellDataReconstruction=1 calls SetCellDataReconstruction(1)):
    (seconds, the filter)."""
    import meshprojection
    f = meshprojection.vtkMeshProjectionFilter()
    f.SetInputData(target)
    f.SetSourceData(source)
    f.SetNumberOfThreads(threads)
    f.SetCacheOperator(False)
    for name, value in properties.items():
        getattr(f, "Set" + name)(value)
    start = time.perf_counter()
    f.Update()
    return time.perf_counter() - start, f


def best_run(target, source, threads, repeats):
    """The best of `repeats` fresh runs of the filter on `threads` threads:
    (seconds, input, neighbours, search, solve, pieces)."""
    best = None
    for _ in range(repeats):
        seconds, f = timed_run(target, source, threads)
        if best is None or seconds < best[0]:
            best = (seconds, f.GetInputTime(), f.GetNeighborsTime(), f.GetSearchTime(), f.GetSolveTime(),
                    f.GetNumberOfIntersections())
    return best


def time_filter(target, source, threads=(1, 2), repeats=2):
    """Prints the best of `repeats` runs of the filter on each thread count,
    with its stages (input, neighbours, search, solve) and pieces."""
    for count in threads:
        print("%d thread(s): %.3f s (input %.3f, neighbours %.3f, search %.3f, solve %.3f), %d pieces" %
              ((count,) + best_run(target, source, count, repeats)))


def find_peer():
    """The path of libsupermesh's library (pip install libsupermesh, into the
    python3 on PATH), for mesh-projection-bench --peer; None without it."""
    try:
        out = subprocess.run(["python3", "-c", "import libsupermesh; print(libsupermesh.get_library())"],
                             capture_output=True, text=True, check=True)
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None


# The filter's stages as mesh-projection-bench --filter-only prints them
# (vtkMeshProjectionFilter::Get*Time), and two parts of the first.
STAGES = ("reading the inputs", "neighbours", "seeding (boundary-cell bins)",
          "search + intersections + integrals", "assembly", "solve", "writing the outputs")
INPUT_PARTS = ("of which id/offset checks", "of which renumbering")


def bench_pair(bench, target, source, options, peer, runs, resample=False):
    """mesh-projection-bench --filter-only on two .vtu files (or, with
    `target` and `source` None, on the pair it generates from `options`'
    --dim and --sizes), with `options` (e.g. ["--threads", "1,2", "--order",
    "asis"]), the peer's intersections in the same process when `peer` is
    given and Resample With Dataset with `resample`: a dict of the cells,
    the intersecting pairs, the filter's best time on the first thread count
    ("filter") and on the second ("filter2", None without), its stages on
    each ("stages", "stages2": {stage: seconds}, with the input's parts),
    the renumbering's time and count, the memory ratio, the peer's time and
    Resample With Dataset's (None without)."""
    command = [bench, "--filter-only", "--runs", str(runs)] + options
    if target:
        command += ["--target", target, "--source", source]
    if peer:
        command += ["--peer", peer]
    if resample:
        command += ["--resample"]
    out = subprocess.run(command, capture_output=True, text=True, check=True).stdout
    number = r"\s+([0-9.eE+-]+)"

    def found(pattern, convert, missing=None):
        m = re.search(pattern, out)
        return convert(m.group(1)) if m else missing

    stages = [{}, {}]  # the first thread count's stages are printed first
    for name in STAGES + INPUT_PARTS:
        for slot, value in enumerate(re.findall(r"\n\s+" + re.escape(name) + number, out)[:2]):
            stages[slot][name] = float(value)
    return {
        "cells": int(re.search(r"target (\d+) cells", out).group(1)),
        "source": int(re.search(r"source (\d+) cells", out).group(1)),
        "pairs": int(re.search(r"(\d+) intersecting pairs", out).group(1)),
        "filter": float(re.search(r"VTK filter \((?:one run|best of \d+)\)" + number, out).group(1)),
        "renumber": float(re.search(r"of which renumbering" + number, out).group(1)),
        "renumbered": int(re.search(r"\((\d) of 2 meshes\)", out).group(1)),
        "memory": found(r"inputs [0-9.]+ MiB, ratio ([^)]+)\)", float, float("nan")),
        "filter2": found(r"VTK filter on \d+ threads" + number, float),
        "stages": stages[0],
        "stages2": stages[1] or None,
        "peer": found(r"libsupermesh intersections only" + number, float),
        "resample": found(r"Resample With Dataset" + number, float),
    }


def print_table(lines, summary, markdown=None):
    """A benchmark's table (markdown rows) and its summary lines, printed and,
    given a file name, written there too."""
    table = "\n".join(lines + [""] + summary)
    print("\n" + table)
    if markdown:
        with open(markdown, "w") as out:
            out.write(table + "\n")
