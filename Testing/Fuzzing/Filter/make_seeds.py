#!/usr/bin/env python3
"""Seeds for FuzzFilter's corpus: byte strings that FuzzFilter.cxx decodes
into meshes that do overlap (triangle, quad, tetrahedron, hexahedron and
polygon meshes on its lattice, with linear arrays, NaN values, a corrupt id),
so that fuzzing starts from inputs that reach the projection, not only the
checks. Keep in step with the decoder (Bytes, MakeMesh, MakeCells, AddArrays).

    Testing/Fuzzing/Filter/make_seeds.py Testing/Fuzzing/Filter/corpus
"""
import hashlib
import itertools
import os
import sys

# Real(): a byte k < 200 is the lattice value (k % 9) / 4 - 0.5.
def lattice(v):
    k = round((v + 0.5) * 4)
    assert 0 <= k < 9
    return k

NAN = 204  # Real(): k >= 200, k % 6 == 0


def grid_points(nx, ny, x0, y0, step, dim, nz=1):
    pts = []
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                p = [x0 + i * step, y0 + j * step]
                if dim == 3:
                    p.append(x0 + k * step)
                pts.append(p)
    return pts


def triangles(nx, ny):
    cells = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            a = j * nx + i
            cells += [(a, a + 1, a + nx + 1), (a, a + nx + 1, a + nx)]
    return cells


def quads(nx, ny):
    return [(j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i)
            for j in range(ny - 1) for i in range(nx - 1)]


def cube_tets(n):
    """Kuhn's 6 tetrahedra per cube of an n^3-point grid."""
    def pid(i, j, k):
        return (k * n + j) * n + i
    cells = []
    for k, j, i in itertools.product(range(n - 1), repeat=3):
        c = [pid(i + a, j + b, k + d) for d in (0, 1) for b in (0, 1) for a in (0, 1)]
        for perm in itertools.permutations((1, 2, 4)):
            path = [0]
            for step in perm:
                path.append(path[-1] + step)
            cells.append(tuple(c[p] for p in path))
    return cells


def hexes(n):
    def pid(i, j, k):
        return (k * n + j) * n + i
    return [(pid(i, j, k), pid(i + 1, j, k), pid(i + 1, j + 1, k), pid(i, j + 1, k),
             pid(i, j, k + 1), pid(i + 1, j, k + 1), pid(i + 1, j + 1, k + 1), pid(i, j + 1, k + 1))
            for k, j, i in itertools.product(range(n - 1), repeat=3)]


def mesh(points, cells, dim, kind="ug", cell_type=None, arrays=((), ()), spoil_id=None):
    """kind: 'ug' (fixed simplex type, or cell_type bytes when given) or 'polys'."""
    out = [0 if kind == "ug" else 2]  # Rare(3): 2 = polydata
    out.append(dim - 2)
    out.append(len(points))
    for p in points:
        out += [lattice(v) for v in p[:dim]]
    out.append(len(cells))
    if kind == "ug":
        out.append(1 if cell_type is not None else 0)  # Rare(2): any type
    else:
        out.append(0)  # (2 + 0) % 4: polygons
    for n, c in enumerate(cells):
        if kind == "ug" and cell_type is not None:
            out.append(cell_type)
        if kind == "polys":
            out.append(len(c) - 3)
        out.append(0)  # not the rare wrong count
        for v in c:
            out.append(240 + 2 if spoil_id == n else v)  # 242: an id of 10^12
    out.append(0)  # offsets not spoiled
    if kind == "ug":
        out.append(0)  # types not truncated
    for values in arrays:  # point arrays, then cell arrays
        out.append(len(values))
        for v in values:
            out += [0, 0]  # one component, a tuple per point/cell
            if v is None:
                out.append(0)  # linear
            else:
                out.append(1)  # Rare(2): explicit values
                out += v
    return bytes(out)


def main(directory):
    os.makedirs(directory, exist_ok=True)
    seeds = []
    # Type bytes: index into FuzzFilter's Types table.
    QUAD, HEX, POLYGON = 2, 5, 8
    t2 = grid_points(5, 5, -0.5, -0.5, 0.5, 2)
    s2 = grid_points(7, 7, -0.25, -0.25, 0.25, 2)
    lin = ((None,), (None,))
    for props in ([0, 0, 0, 0], [1, 2, 0, 1], [6, 31, 1, 1], [2, 17, 0, 0]):
        seeds.append(bytes(props) + mesh(t2, triangles(5, 5), 2, arrays=lin)
                     + mesh(s2, triangles(7, 7), 2, arrays=lin))
    nan_values = [[NAN if i == 20 else 8] for i in range(len(s2))]
    seeds.append(bytes([0, 0, 0, 0]) + mesh(t2, triangles(5, 5), 2)
                 + mesh(s2, triangles(7, 7), 2, arrays=(([x for v in nan_values for x in v],), ())))
    seeds.append(bytes([0, 0, 0, 0]) + mesh(t2, quads(5, 5), 2, cell_type=QUAD, arrays=lin)
                 + mesh(s2, quads(7, 7), 2, kind="polys", arrays=lin))
    seeds.append(bytes([0, 0, 0, 0]) + mesh(t2, triangles(5, 5), 2)
                 + mesh(s2, triangles(7, 7), 2, arrays=lin, spoil_id=3))
    t3 = grid_points(3, 3, -0.5, -0.5, 0.75, 3, nz=3)
    s3 = grid_points(4, 4, -0.25, -0.25, 0.5, 3, nz=4)
    seeds.append(bytes([0, 0, 0, 0]) + mesh(t3, cube_tets(3), 3, arrays=lin)
                 + mesh(s3, cube_tets(4), 3, arrays=lin))
    seeds.append(bytes([1, 8, 0, 1]) + mesh(t3, hexes(3), 3, cell_type=HEX, arrays=lin)
                 + mesh(s3, cube_tets(4), 3, arrays=lin))
    for seed in seeds:
        name = hashlib.sha1(seed).hexdigest()
        with open(os.path.join(directory, name), "wb") as f:
            f.write(seed)
    print(f"{len(seeds)} seeds in {directory}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "corpus"))
