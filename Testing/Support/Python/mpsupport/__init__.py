"""MeshProjection's test support, shared by the tests and the benchmarks.

    testing     checks and their summary, sample data, exact P1 integrals,
                image comparison, time series, blocks and multiblock files
    meshes      jittered grids of quads, triangles, hexahedra, tetrahedra
    gmshmeshes  surfaces, curves and volumes meshed by Gmsh (python3-gmsh)
    mpi         the MPI controller and collectives for pvbatch --symmetric
    fringe      the fringe's fields and measure (interior points)
    secondorder copies of meshes, fields and projections of the second-order tests

Not installed: the build copies it next to the `meshprojection` package
(<build>/lib/python3/dist-packages), which ctest puts on PYTHONPATH; run a
benchmark script with that directory on PYTHONPATH (Benchmarks/README.md).
"""
