// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file TetrahedronClipping.h
 * @brief The two clippers behind TetrahedronIntersector (private to it and
 *        to its tests), one include for all their parts.
 *
 * ClipByPlane splits a tetrahedron by a plane into at most three (the
 * reference clipper); VertexGraph keeps the clipped cell as a convex
 * polyhedron whose vertices each have three neighbours (the fast one), its
 * first two cuts from tables of the topologies they make. Both classify the
 * corners of the clipped cell with FaceSides, exactly signed. The parts,
 * one concern each:
 *   FaceSides.h          the corners' sides of the other cell's face planes
 *   ClipByPlane.h        the reference clipper, tetrahedron by tetrahedron
 *   VertexGraph.h        the fast clipper's polyhedron and its cut by a plane
 *   VertexGraphTables.h  its first two cuts from tables
 *   VertexGraphFaces.h   its faces, and the piece's tetrahedra from them
 *   PieceMoments.h       the moments of a piece, tetrahedron by tetrahedron
 */
#ifndef MeshProjection_Kernel_TetrahedronClipping_h
#define MeshProjection_Kernel_TetrahedronClipping_h

#include "Geometry/ClipByPlane.h"
#include "Geometry/FaceSides.h"
#include "Geometry/PieceMoments.h"
#include "Geometry/VertexGraph.h"

#endif
