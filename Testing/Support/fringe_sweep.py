"""The fringe on Gmsh pairs that overlap in part: a table per pair and shift.

    PYTHONPATH=BUILD/lib/python3/dist-packages /usr/bin/python3 Testing/Support/fringe_sweep.py [FILTER] [--refine K]
        [--shifts random:N:SEED]

Input is a Gmsh mesh of the unit square or cube moved by a shift, the
Source another (finer or coarser) of the same domain; FILTER keeps the pairs
whose name contains it. Per pair, with the default settings, on the smooth
field sin(2x)cos(3y)+z^2 as point data (s) and as cell data to points (c):

  s, c      worst error at a valid point / worst at interior points (every
            cell around the point fully covered: Python.Fringe's interior)
  cL        c with the Source's cell data reconstructed linear
            (CellDataReconstruction 2): second order on each cell, where
            constant cells (c) give free points beside the fringe a
            one-sided mean of first order
  s10, c10  s and c over the valid points covered 10% or more only
  s1, c1    the same over interior points at least one ring from the fringe
            (every cell around the point's neighbours fully covered too)
  sF, cF    the worst error at free valid points that are not interior (the
            values an extension carries) over the worst at interior points
  linear    worst error of 1 + 2x - 3y + 0.5z at a valid point / its range
  >10%      points whose support is covered 10% or more left invalid
  sliver    the "valid through slivers only" warning fired
  interior  the number of interior points (the denominators' points)
  worst s, worst c
            the point of the worst s (c): its covered fraction, whether it is
            aggregated (A), free (F), and its distance to the covered part in
            cells (rings to a fully covered cell); for an aggregated one its
            error split as the extension's own (sum_k w_k f(x_k) - f(x_i))
            and the free values' errors it carries (sum_k w_k e_k), both
            over the interior's worst error, and its weights' sum |w|

--shifts random:N:SEED runs, instead of each kind's standard five shifts,
N shifts drawn with that seed (each coordinate of magnitude 0.15 to 0.45,
its sign random; z = 0 in 2D) after two that the standard ones miss; the
last line gives the worst s and c of each kind over its shifts.

The mixed pairs use Testing/Data/Gmsh's meshes (mixed_box: hexahedra,
wedges, tetrahedra and pyramids): Gmsh 4.8 (python3-gmsh) often aborts in
an Eigen assertion making such meshes, and what it makes depends on what
it meshed before in the process. Each kind of pair runs in a child
process, tried again up to three times, so that such an abort loses only
its rows (said in a line).
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from meshprojection import fringe_extension, operator_matrices
from mpsupport import gmshmeshes
from mpsupport.fringe import fully_covered, linear, point_cells, project, smooth, with_fields
from mpsupport.testing import mortar

SHIFTS_3D = [(0.27, 0.13, 0.21), (-0.33, 0.41, 0.07), (-0.2, 0.33, 0.11), (0.17, 0.29, 0.07), (0.27, -0.19, 0.13)]
SHIFTS_2D = [(0.31, 0.17, 0), (-0.2, 0.33, 0), (0.17, 0.29, 0), (0.27, -0.19, 0), (0.4, 0.1, 0)]


# Shifts the standard ones miss: a tetrahedral pair with a coarse Input at
# (-0.29, -0.23, 0.17), a hexahedral one at (0.21, 0.37, -0.15).
SHIFTS_EXTRA = [(-0.29, -0.23, 0.17), (0.21, 0.37, -0.15)]


def random_shifts(count, seed, dimension):
    """`count` shifts of magnitude 0.15 to 0.45 per coordinate, random signs."""
    rng = np.random.default_rng(seed)
    shifts = []
    for _ in range(count):
        s = rng.uniform(0.15, 0.45, 3) * rng.choice([-1.0, 1.0], 3)
        s = np.round(s, 2)
        if dimension == 2:
            s[2] = 0.0
        shifts.append(tuple(float(v) for v in s))
    return shifts


def stored(name):
    """A mesh of Testing/Data/Gmsh (the mixed one: Gmsh 4.8 aborts making it)."""
    from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Data", "Gmsh", name + ".vtu"))
    reader.Update()
    return reader.GetOutput()


def kinds():
    """(name, make(h), Input's h, Source's h, shifts) of every kind of pair
    (for the stored meshes, h is the file's name)."""
    g = gmshmeshes
    three = [
        ("tets", lambda h: g.volume("box", h), 0.08, 0.104),
        ("tets coarse Input", lambda h: g.volume("box", h), 0.104, 0.08),
        ("wedges", g.wedges, 0.08, 0.104),
        ("wedges coarse Input", g.wedges, 0.104, 0.08),
        ("pyramids", g.pyramids, 0.15, 0.195),
        ("pyramids coarse Input", g.pyramids, 0.195, 0.15),
        ("hexes", lambda h: g.hexahedra(h), 0.08, 0.1),
        ("hexes coarse Input", lambda h: g.hexahedra(h), 0.1, 0.0714),
        ("hexes unstructured", lambda h: g.hexahedra(h, structured=False), 0.15, 0.195),
        ("mixed", stored, "mixed_box", "mixed_box"),
        ("mixed, hexahedra Source", stored, "mixed_box", "hexes_box"),
        ("tets Input, mixed Source", stored, "tets_box", "mixed_box"),
    ]
    two = [
        ("2D triangles", lambda h: g.planar(h), 0.05, 0.065),
        ("2D quads", lambda h: g.planar(h, quads=True), 0.05, 0.065),
        ("2D quads coarse Input", lambda h: g.planar(h, quads=True), 0.065, 0.05),
        ("2D mixed", g.planar_mixed, 0.05, 0.065),
        ("2D disk Source", None, 0.05, 0.065),
    ]
    return [k + (SHIFTS_3D,) for k in three] + [k + (SHIFTS_2D,) for k in two]


def neighbours(out):
    """Per point, the cells around it and the points sharing a cell with it."""
    cells = point_cells(out)
    corners = [[out.GetCell(c).GetPointId(k) for k in range(out.GetCell(c).GetNumberOfPoints())]
               for c in range(out.GetNumberOfCells())]
    points = [sorted({q for c in around for q in corners[c]}) for around in cells]
    return cells, points


def measure(target, source, around, near, whole):
    f, out, texts = project(target, source)
    x = vtk_to_numpy(out.GetPoints().GetData())
    pd, cd = out.GetPointData(), out.GetCellData()
    valid = vtk_to_numpy(pd.GetArray("vtkValidPointMask")).astype(bool)
    cover = vtk_to_numpy(cd.GetArray("CoveredFraction"))
    full = fully_covered(cover, around)
    interior = valid & full
    deep = interior & np.array([all(full[q] for q in ring) for ring in near])
    row = {"interior": int(interior.sum())}
    worst, split = {}, {}
    extensions = {"s": fringe_extension(f).tocsr(), "c": fringe_extension(f, "cells_to_points").tocsr()}
    aggregated = {name: P.getnnz(axis=0) == 0 for name, P in extensions.items()}
    exact_s = smooth(x)
    for name in ("s", "c"):
        P = extensions[name]
        signed = vtk_to_numpy(pd.GetArray(name)) - exact_s
        error = np.abs(signed)
        row[name] = np.max(error[valid]) / np.max(error[interior])
        row[name + "1"] = np.max(error[valid]) / np.max(error[deep]) if deep.any() else np.nan
        row[name + "F"] = np.max(error[valid & ~full & ~aggregated[name]], initial=0) / np.max(error[interior])
        worst[name] = int(np.argmax(np.where(valid, error, -1)))
        w = P.getrow(worst[name])
        split[name] = (abs(w.dot(exact_s)[0] - exact_s[worst[name]]) / np.max(error[interior]),
                       abs(w.dot(signed)[0]) / np.max(error[interior]), np.abs(w.data).sum())
    linear_cells = mortar(target, source, pieces=False, CellDataTarget=1, CellDataReconstruction=2).GetOutput()
    error = np.abs(vtk_to_numpy(linear_cells.GetPointData().GetArray("c")) - exact_s)
    row["cL"] = np.max(error[valid]) / np.max(error[interior])
    exact = linear(x)
    row["linear"] = np.max(np.abs(vtk_to_numpy(pd.GetArray("l"))[valid] - exact[valid])) / np.ptp(exact)
    m_tt, _, reached = operator_matrices(f)
    fraction = np.asarray(m_tt.sum(axis=1)).ravel() / whole
    row["invalid10"] = int((reached & ~valid & (fraction >= 0.1)).sum())
    row["sliver"] = any("valid through slivers only" in t for t in texts)
    for name in ("s", "c"):
        signed = vtk_to_numpy(pd.GetArray(name)) - exact_s
        kept = valid & (fraction >= 0.1)
        row[name + "10"] = np.max(np.abs(signed)[kept], initial=0) / np.max(np.abs(signed)[interior])
    for name in ("s", "c"):
        # Rings from the worst point to a fully covered cell.
        start = worst[name]
        ring, seen, distance = {start}, {start}, 0
        while distance < 12 and not any(full[p] for p in ring):
            ring = {q for p in ring for q in near[p]} - seen
            seen |= ring
            distance += 1
        row["worst " + name] = "%.3f %s %d" % (fraction[start], "A" if aggregated[name][start] else "F", distance)
        if aggregated[name][start]:
            row["worst " + name] += " own %.2f carried %.2f |w| %.1f" % split[name]
    return row


def run_in_child(name, tries=3):
    """In the parent: runs the kind in a child process, again when it
    aborts (up to `tries` times); True. In the child: False."""
    for _ in range(tries):
        child = os.fork()
        if not child:
            return False
        _, status = os.waitpid(child, 0)
        if not status:
            return True
    print("%-26s failed %d times (status %d): Gmsh aborted" % (name, tries, status), flush=True)
    return True


def main():
    args = sys.argv[1:]
    refine = 1.0
    if "--refine" in args:
        k = args.index("--refine")
        refine = float(args[k + 1])
        del args[k:k + 2]
    shifts_rule = None
    if "--shifts" in args:
        k = args.index("--shifts")
        shifts_rule = args[k + 1]
        del args[k:k + 2]
    pick = args[0] if args else ""
    print("%-26s %-20s %6s %6s %6s %6s %6s %6s %6s %6s %6s %8s %5s %6s %8s  %-42s %s" %
          ("pair", "shift", "s", "c", "s10", "c10", "cL", "s1", "c1", "sF", "cF", "linear", ">10%", "sliver", "interior",
           "worst s (cover, A/F, rings; own, carried)", "worst c"))
    for name, make, h_in, h_src, shifts in kinds():
        if pick not in name or (refine != 1.0 and make is stored):
            continue
        if refine != 1.0:
            h_in, h_src = h_in / refine, h_src / refine
        if shifts_rule:
            _, count, seed = shifts_rule.split(":")
            dimension = 2 if shifts is SHIFTS_2D else 3
            extra = SHIFTS_EXTRA if dimension == 3 else [(x, y, 0.0) for x, y, _ in SHIFTS_EXTRA]
            shifts = extra + random_shifts(int(count), int(seed), dimension)
        if run_in_child(name):
            continue
        if make is None:
            base, source = gmshmeshes.planar(h_in), gmshmeshes.surface("disk", h_src)
        else:
            base, source = make(h_in), make(h_src)
        source = with_fields(source)
        worst_s, worst_c = (0.0, ()), (0.0, ())
        for shift in shifts:
            target = gmshmeshes.moved(base, translate=shift)
            around, near = neighbours(target)
            whole_f = mortar(target, with_fields(target), pieces=False, CacheOperator=True)
            whole = np.asarray(operator_matrices(whole_f)[0].sum(axis=1)).ravel()
            r = measure(target, source, around, near, whole)
            print("%-26s %-20s %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f %8.1e %5d %6s %8d  %-42s %s" %
                  (name, "(%g,%g,%g)" % shift, r["s"], r["c"], r["s10"], r["c10"], r["cL"], r["s1"], r["c1"], r["sF"], r["cF"], r["linear"],
                   r["invalid10"],
                   "yes" if r["sliver"] else "-", r["interior"], r["worst s"], r["worst c"]), flush=True)
            worst_s, worst_c = max(worst_s, (r["s"], shift)), max(worst_c, (r["c"], shift))
        print("%-26s worst s %.2f at (%g,%g,%g), worst c %.2f at (%g,%g,%g)" %
              ((name, worst_s[0]) + worst_s[1] + (worst_c[0],) + worst_c[1]), flush=True)
        os._exit(0)


if __name__ == "__main__":
    main()
