"""Surface meshes made by Gmsh (python3-gmsh), as VTK data: the tests' and
the examples' real-generator pairs (curved, with sharp edges, quads, open
boundaries, several pieces). Every mesh is cached per process."""
import numpy as np

_cache = {}


def _occ(shape):
    """Adds `shape` to Gmsh's OpenCASCADE kernel; returns the surfaces to
    reverse (a shell's inner side faces inward) and those to leave out (the
    flat face closing a cap)."""
    import gmsh
    occ = gmsh.model.occ
    reverse = []
    skip = []
    if shape == "sphere":
        occ.addSphere(0, 0, 0, 1.0)
    elif shape == "cylinder":
        occ.addCylinder(0, 0, -1, 0, 0, 2, 0.8)
    elif shape == "torus":
        occ.addTorus(0, 0, 0, 1.0, 0.4)
    elif shape == "box":
        occ.addBox(0, 0, 0, 1, 1, 1)
    elif shape == "cap":
        # An open surface with a boundary: the sphere's part above z = 0.3.
        occ.addSphere(0, 0, 0, 1.0, 1, np.arcsin(0.3), np.pi / 2)
    elif shape == "shell":
        occ.addSphere(0, 0, 0, 1.0, 1)
        occ.addSphere(0, 0, 0, 0.97, 2)
        occ.cut([(3, 1)], [(3, 2)])
    elif shape.startswith("arc"):
        # A quarter of the side of a cylinder of radius r (arc<r>): two of
        # them make a curved gap.
        occ.addCylinder(0, 0, 0, 0, 0, 1, float(shape[3:]), 1, np.pi / 2)
    elif shape == "disk":
        occ.addDisk(0, 0, 0, 1.0, 1.0)
    elif shape.startswith("patch"):
        # A flat square at height z (patch<z>): two patches make a gap.
        z = float(shape[5:])
        occ.addRectangle(0, 0, z, 1, 1)
    else:
        raise ValueError(shape)
    occ.synchronize()
    for dim, tag in gmsh.model.getEntities(2):
        box = gmsh.model.getBoundingBox(2, tag)
        if shape == "shell" and box[3] - box[0] < 1.99:  # the inner sphere (diameter 1.94)
            reverse.append(tag)
        if shape == "cap" and box[5] - box[2] < 1e-6:  # the flat disk under the cap
            skip.append(tag)
        if shape.startswith("arc") and min(box[3] - box[0], box[4] - box[1], box[5] - box[2]) < 1e-6:
            skip.append(tag)  # the flat faces of the cylinder's wedge
    return reverse, skip


def _generate(name, dim, build, h, options=()):
    """Meshes what `build()` adds to Gmsh (it returns the entities of
    dimension `dim` to reverse and to leave out) with size `h`; returns the
    node coordinates and the cells (lists of indices into them), in Gmsh's
    own node and element order."""
    import gmsh
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(name)
        reverse, skip = build()
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        for option, value in options:
            gmsh.option.setNumber(option, value)
        gmsh.model.mesh.generate(dim)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        index = {int(t): i for i, t in enumerate(tags)}
        x = np.asarray(coords).reshape(-1, 3)
        cells = []
        for _, tag in gmsh.model.getEntities(dim):
            if tag in skip:
                continue
            types, _, nodes = gmsh.model.mesh.getElements(dim, tag)
            for etype, enodes in zip(types, nodes):
                corners = {1: 2, 2: 3, 3: 4, 4: 4, 5: 8, 6: 6}[int(etype)]
                block = np.vectorize(index.get)(np.asarray(enodes, dtype=np.int64)).reshape(-1, corners)
                if tag in reverse:
                    block = block[:, ::-1]
                cells.extend(list(c) for c in block)
    finally:
        gmsh.finalize()
    return x, cells


def _polydata(x, cells, lines):
    """vtkPolyData of `cells` (polygons, or lines) on the nodes they use, in Gmsh's order."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    # Only the nodes the cells use (a skipped entity leaves its own).
    connectivity = np.concatenate([np.asarray(c, dtype=np.int64) for c in cells])
    used = np.unique(connectivity)
    renumber = np.full(len(x), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    connectivity = renumber[connectivity]
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x[used]), deep=True))
    offsets = np.cumsum([0] + [len(c) for c in cells]).astype(np.int64)
    array = vtkCellArray()
    array.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True), numpy_to_vtkIdTypeArray(connectivity, deep=True))
    mesh = vtkPolyData()
    mesh.SetPoints(points)
    if lines:
        mesh.SetLines(array)
    else:
        mesh.SetPolys(array)
    return mesh


def surface(shape, h, algorithm=6, quads=False):
    """vtkPolyData of the triangles (or quads) Gmsh makes on `shape` with
    size `h` and 2D algorithm `algorithm` (5 Delaunay, 6 Frontal-Delaunay,
    1 MeshAdapt), in Gmsh's own node and element order, shared points merged."""
    key = (shape, h, algorithm, quads)
    if key not in _cache:
        options = [("Mesh.Algorithm", algorithm)] + ([("Mesh.RecombineAll", 1)] if quads else [])
        x, cells = _generate(shape, 2, lambda: _occ(shape), h, options)
        _cache[key] = _polydata(x, cells, lines=False)
    return _cache[key]


def moved(mesh, rotate_x=0.0, translate=(0.0, 0.0, 0.0)):
    """`mesh` turned by `rotate_x` degrees about the x axis, then translated."""
    from vtkmodules.vtkCommonTransforms import vtkTransform
    from vtkmodules.vtkFiltersGeneral import vtkTransformFilter
    transform = vtkTransform()
    transform.Translate(*translate)
    transform.RotateX(rotate_x)
    result = vtkTransformFilter()
    result.SetTransform(transform)
    result.SetInputData(mesh)
    result.Update()
    return result.GetOutput()


def with_point_field(mesh, name, f):
    """A shallow copy of `mesh` with the point array f(x, y, z)."""
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    copy = mesh.NewInstance()
    copy.ShallowCopy(mesh)
    x = vtk_to_numpy(mesh.GetPoints().GetData())
    values = numpy_to_vtk(np.ascontiguousarray(f(x[:, 0], x[:, 1], x[:, 2]), dtype=np.float64), deep=True)
    values.SetName(name)
    copy.GetPointData().AddArray(values)
    return copy


def curve(shape, h):
    """vtkPolyData of the segments (VTK_LINE cells) Gmsh makes on the curve
    `shape` with size `h`, in Gmsh's order: "circle" (radius 1), "square"
    (the boundary of the unit square: corners), "spline" (an open B-spline
    through points in 3D), "wave" (an open interface y = 0.2 sin(2 pi x)
    between two 2D subdomains)."""
    key = ("curve", shape, h)
    if key in _cache:
        return _cache[key]

    def build():
        import gmsh
        occ = gmsh.model.occ
        if shape == "circle":
            occ.addCircle(0, 0, 0, 1.0)
        elif shape == "square":
            occ.addRectangle(0, 0, 0, 1, 1)
        elif shape == "spline":
            occ.addBSpline([occ.addPoint(np.cos(t), np.sin(t), 0.3 * t) for t in np.linspace(0, 4, 9)])
        elif shape == "wave":
            occ.addSpline([occ.addPoint(x, 0.2 * np.sin(2 * np.pi * x), 0) for x in np.linspace(0, 1, 17)])
        else:
            raise ValueError(shape)
        occ.synchronize()
        return [], []

    x, cells = _generate(shape, 1, build, h)
    _cache[key] = _polydata(x, cells, lines=True)
    return _cache[key]


def volume(shape, h):
    """vtkUnstructuredGrid of the tetrahedra Gmsh makes in `shape` ("sphere":
    the unit ball, "box": the unit cube) with size `h`, in Gmsh's order."""
    key = ("volume", shape, h)
    if key not in _cache:
        from vtkmodules.vtkCommonCore import vtkPoints
        from vtkmodules.vtkCommonDataModel import VTK_TETRA, vtkCellArray, vtkUnstructuredGrid
        from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
        x, cells = _generate(shape, 3, lambda: _occ(shape), h)
        points = vtkPoints()
        points.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=True))
        connectivity = np.asarray(cells, dtype=np.int64).ravel()
        offsets = np.arange(0, len(connectivity) + 1, 4, dtype=np.int64)
        array = vtkCellArray()
        array.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True), numpy_to_vtkIdTypeArray(connectivity, deep=True))
        grid = vtkUnstructuredGrid()
        grid.SetPoints(points)
        grid.SetCells(VTK_TETRA, array)
        _cache[key] = grid
    return _cache[key]


def _grid(x, cells, cell_type):
    """vtkUnstructuredGrid of `cells` (all of one VTK type) on the nodes `x`."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkUnstructuredGrid
    from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x), deep=True))
    connectivity = np.asarray(cells, dtype=np.int64)
    corners = connectivity.shape[1]
    connectivity = connectivity.ravel()
    offsets = np.arange(0, len(connectivity) + 1, corners, dtype=np.int64)
    array = vtkCellArray()
    array.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True), numpy_to_vtkIdTypeArray(connectivity, deep=True))
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.SetCells(cell_type, array)
    return grid


def planar(h, quads=False, algorithm=6):
    """The unit square in the plane z = 0 meshed by Gmsh with size `h`:
    triangles, or quads (recombined), as a vtkPolyData (a 2D mesh)."""
    return surface("patch0", h, algorithm, quads)


def wedges(h, height=1.0):
    """The unit square meshed by Gmsh with size `h`, extruded along z over
    `height` in layers of about `h`: a vtkUnstructuredGrid of wedges."""
    key = ("wedges", h, height)
    if key not in _cache:
        from vtkmodules.vtkCommonDataModel import VTK_WEDGE

        def build():
            import gmsh
            occ = gmsh.model.occ
            occ.addRectangle(0, 0, 0, 1, 1)
            occ.extrude([(2, 1)], 0, 0, height, numElements=[max(1, int(round(height / h)))], recombine=True)
            occ.synchronize()
            return [], []
        x, cells = _generate("wedges", 3, build, h)
        cells = np.asarray(cells, dtype=np.int64)
        # VTK's wedge: the triangle (0, 1, 2) turns away from (3, 4, 5).
        a, b, c = x[cells[:, 0]], x[cells[:, 1]], x[cells[:, 2]]
        up = x[cells[:, 3:]].mean(axis=1) - x[cells[:, :3]].mean(axis=1)
        toward = np.einsum("ij,ij->i", np.cross(b - a, c - a), up) > 0
        cells[toward] = cells[toward][:, [0, 2, 1, 3, 5, 4]]
        _cache[key] = _grid(x, cells, VTK_WEDGE)
    return _cache[key]


def hexahedra(h, structured=True):
    """The unit cube meshed by Gmsh into hexahedra of size about `h`, a
    vtkUnstructuredGrid (Gmsh's hexahedron orders its corners as VTK's
    does): structured (transfinite and recombined, round(1/h) cells per
    edge), or not (Gmsh's tetrahedra of size `h` each split into four
    hexahedra: Mesh.SubdivisionAlgorithm 2)."""
    key = ("hexahedra", h, structured)
    if key not in _cache:
        from vtkmodules.vtkCommonDataModel import VTK_HEXAHEDRON

        def build():
            import gmsh
            gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
            gmsh.model.occ.synchronize()
            mesh = gmsh.model.mesh
            for _, tag in gmsh.model.getEntities(1) if structured else []:
                mesh.setTransfiniteCurve(tag, int(round(1 / h)) + 1)
            for _, tag in gmsh.model.getEntities(2) if structured else []:
                mesh.setTransfiniteSurface(tag)
                mesh.setRecombine(2, tag)
            for _, tag in gmsh.model.getEntities(3) if structured else []:
                mesh.setTransfiniteVolume(tag)
            return [], []
        options = [] if structured else [("Mesh.SubdivisionAlgorithm", 2)]
        x, cells = _generate("hexahedra", 3, build, h, options)
        _cache[key] = _grid(x, np.asarray(cells, dtype=np.int64), VTK_HEXAHEDRON)
    return _cache[key]


# Gmsh element type -> (VTK cell type, VTK node i is Gmsh node order[i]);
# a prism's base triangle turns towards its top in Gmsh, away in VTK.
_GMSH_TO_VTK = {2: (5, [0, 1, 2]), 3: (9, [0, 1, 2, 3]), 4: (10, [0, 1, 2, 3]),
                5: (12, list(range(8))), 6: (13, [0, 2, 1, 3, 5, 4]), 7: (14, list(range(5)))}


def _mixed_grid(name, dim, build, h):
    """vtkUnstructuredGrid of every element of dimension `dim` that Gmsh
    makes on what `build()` adds (it sets its own meshing constraints),
    with size `h`, of any linear type, in Gmsh's order."""
    import gmsh
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(name)
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        build()
        gmsh.model.mesh.generate(dim)
        x, cells = _typed_cells(dim, _GMSH_TO_VTK)
    finally:
        gmsh.finalize()
    return _typed_grid(x, cells)


def _typed_cells(dim, table):
    """Gmsh's nodes and its elements of dimension `dim`, each as (VTK type,
    indices into the nodes in VTK's order) through `table` (Gmsh element
    type -> (VTK type, VTK node i is Gmsh node order[i]))."""
    import gmsh
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {int(t): i for i, t in enumerate(tags)}
    x = np.asarray(coords).reshape(-1, 3)
    cells = []
    for etype, _, enodes in zip(*gmsh.model.mesh.getElements(dim)):
        vtk_type, order = table[int(etype)]
        block = np.asarray(enodes, dtype=np.int64).reshape(-1, len(order))[:, order]
        cells.extend((vtk_type, [index[int(t)] for t in c]) for c in block)
    return x, cells


def _typed_grid(x, cells):
    """vtkUnstructuredGrid of `cells` ((VTK type, node indices), of any
    types) on the nodes of `x` they use, in their order."""
    from vtkmodules.vtkCommonCore import vtkPoints
    from vtkmodules.vtkCommonDataModel import vtkUnstructuredGrid
    from vtkmodules.util.numpy_support import numpy_to_vtk
    used = np.unique(np.concatenate([c for _, c in cells]))
    renumber = np.full(len(x), -1, dtype=np.int64)
    renumber[used] = np.arange(len(used))
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(x[used]), deep=True))
    grid = vtkUnstructuredGrid()
    grid.SetPoints(points)
    grid.Allocate(len(cells))
    for vtk_type, c in cells:
        grid.InsertNextCell(vtk_type, len(c), [int(renumber[k]) for k in c])
    return grid


def planar_mixed(h):
    """The unit square in the plane z = 0 meshed by Gmsh with size `h`:
    triangles for x < 0.5, quads (recombined) for x > 0.5, a
    vtkUnstructuredGrid of both."""
    key = ("planar_mixed", h)
    if key not in _cache:
        def build():
            import gmsh
            occ = gmsh.model.occ
            occ.addRectangle(0, 0, 0, 0.5, 1, 1)
            occ.addRectangle(0.5, 0, 0, 0.5, 1, 2)
            occ.fragment([(2, 1)], [(2, 2)])
            occ.synchronize()
            for _, s in gmsh.model.getEntities(2):
                if occ.getCenterOfMass(2, s)[0] > 0.5:
                    gmsh.model.mesh.setRecombine(2, s)
        _cache[key] = _mixed_grid("planar_mixed", 2, build, h)
    return _cache[key]


def pyramids(h):
    """Gmsh's unstructured hexahedra of size `h` (hexahedra(h, False)), each
    cut into six pyramids about its centroid (Gmsh makes pyramids only to
    close quads against tetrahedra): a vtkUnstructuredGrid of pyramids."""
    key = ("pyramids", h)
    if key not in _cache:
        from vtkmodules.vtkCommonDataModel import VTK_PYRAMID
        from vtkmodules.util.numpy_support import vtk_to_numpy
        hexes = hexahedra(h, structured=False)
        x = vtk_to_numpy(hexes.GetPoints().GetData())
        corners = vtk_to_numpy(hexes.GetCells().GetConnectivityArray()).reshape(-1, 8)
        apex = len(x) + np.arange(len(corners))
        x = np.vstack([x, x[corners].mean(axis=1)])
        # VTK's hexahedron's faces, each turning towards the centroid (a
        # pyramid's base turns towards its apex).
        faces = [(0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7), (0, 3, 2, 1), (4, 5, 6, 7)]
        cells = np.concatenate([np.column_stack([corners[:, f], apex]) for f in faces])
        base = x[cells[:, :4]]
        normal = np.cross(base[:, 2] - base[:, 0], base[:, 3] - base[:, 1])
        away = np.einsum("ij,ij->i", normal, x[cells[:, 4]] - base.mean(axis=1)) < 0
        cells[away] = cells[away][:, [0, 3, 2, 1, 4]]
        _cache[key] = _grid(x, cells, VTK_PYRAMID)
    return _cache[key]


# Gmsh's second-order element types -> (VTK cell type, VTK node i is Gmsh
# node order[i]): the mid-edge nodes of tetrahedra, hexahedra and prisms and
# the mid-face nodes are numbered differently (Gmsh's reference elements
# against VTK's GetParametricCoords()).
_HEX20 = [0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15]
_PRISM15 = [0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11]
_GMSH2_TO_VTK = {8: (21, [0, 1, 2]), 9: (22, list(range(6))), 16: (23, list(range(8))),
                 10: (28, list(range(9))), 11: (24, [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]),
                 17: (25, _HEX20), 12: (29, _HEX20 + [22, 23, 21, 24, 20, 25, 26]),
                 18: (26, _PRISM15), 13: (32, _PRISM15 + [15, 17, 16])}


def second_order(shape, h, quads=False, incomplete=False):
    """vtkUnstructuredGrid of Gmsh's order-2 mesh (gmsh.model.mesh.setOrder(2))
    of `shape` with size `h`: "square" (the unit square, z = 0), "disk" (the
    unit disk: its boundary mid nodes on the circle), "cube" (the unit cube:
    tetrahedra), "ball" (the ball of radius 0.5 about (0.5, 0.5, 0.5):
    tetrahedra, the boundary mid nodes on the sphere), "hexes" (the unit cube, structured: hexahedra) or "prisms"
    (the unit square extruded over 1: wedges) or "unitball" (the unit ball about
    the origin: tetrahedra, its boundary mid nodes on the sphere). `quads`: 2D cells recombined
    into quadrilaterals; `incomplete`: serendipity cells (Quad8, Hexa20,
    Wedge15: Mesh.SecondOrderIncomplete), else Quad9, Hexa27, Wedge18."""
    key = ("second_order", shape, h, quads, incomplete)
    if key in _cache:
        return _cache[key]
    import gmsh
    dim = 3 if shape in ("cube", "hexes", "prisms", "ball", "unitball") else 2
    gmsh.initialize()
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("second_order")
        occ = gmsh.model.occ
        mesh = gmsh.model.mesh
        if shape == "square":
            occ.addRectangle(0, 0, 0, 1, 1)
        elif shape == "disk":
            occ.addDisk(0, 0, 0, 1.0, 1.0)
        elif shape in ("cube", "hexes"):
            occ.addBox(0, 0, 0, 1, 1, 1)
        elif shape == "ball":
            occ.addSphere(0.5, 0.5, 0.5, 0.5)
        elif shape == "unitball":
            occ.addSphere(0, 0, 0, 1.0)
        elif shape == "prisms":
            occ.addRectangle(0, 0, 0, 1, 1)
            occ.extrude([(2, 1)], 0, 0, 1, numElements=[max(1, int(round(1 / h)))], recombine=True)
        else:
            raise ValueError(shape)
        occ.synchronize()
        if shape == "hexes":
            for _, tag in gmsh.model.getEntities(1):
                mesh.setTransfiniteCurve(tag, int(round(1 / h)) + 1)
            for _, tag in gmsh.model.getEntities(2):
                mesh.setTransfiniteSurface(tag)
                mesh.setRecombine(2, tag)
            for _, tag in gmsh.model.getEntities(3):
                mesh.setTransfiniteVolume(tag)
        gmsh.option.setNumber("Mesh.MeshSizeMin", h)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
        gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 1 if incomplete else 0)
        if quads:
            gmsh.option.setNumber("Mesh.RecombineAll", 1)
        mesh.generate(dim)
        mesh.setOrder(2)
        x, cells = _typed_cells(dim, _GMSH2_TO_VTK)
    finally:
        gmsh.finalize()
    _cache[key] = _typed_grid(x, cells)
    return _cache[key]
