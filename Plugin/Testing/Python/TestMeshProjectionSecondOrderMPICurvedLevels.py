"""CurvedCellSubdivision 2 and 3 on several MPI processes (run under
mpiexec with pvbatch --mpi --symmetric): curved Gmsh tri6 and quad9 disks
and tet10 balls that overlap in part, as Input and as Source, with the
fringe, give the serial masks, values, integrals and warnings
(mpsupport.secondorder.check_curved_levels). (Python.SecondOrderMPI2 runs
the same checks on 2 processes.)
"""
from mpsupport import mpi
from mpsupport.secondorder import check_curved_levels

controller, rank, size, check = mpi.begin()

import meshprojection  # noqa: E402,F401  (after MPI is up)

check_curved_levels(controller, check)
check.finish("%d processes, curved levels" % size)
