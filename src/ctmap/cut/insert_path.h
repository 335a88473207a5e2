#pragma once
/// \file insert_path.h
/// Inserting a path (paper §2.3: "the path inserted into the mesh") and single points into the
/// work mesh by splitting faces: the surface is never changed, every new vertex lies on it.
#include <map>
#include <vector>

#include "ctmap/cut/work_mesh.h"

namespace ctmap {

/// One point of a path on the mesh: a vertex, or the point a + t (b - a) inside edge {a, b}.
struct PathNode {
    int vertex = -1;  ///< >= 0 for a mesh vertex
    int a = -1, b = -1;
    double t = 0;
    int face = -1;  ///< the face crossed to reach this node from the previous one (-1: along an edge)
};

/// Inserts the path `nodes` (consecutive nodes share a face, or an edge when `face` is -1) into
/// `mesh`: edge points become vertices, every face the path crosses is re-triangulated (CGAL's
/// constrained Delaunay triangulation in the face's affine frame) so that consecutive path
/// vertices are joined by mesh edges. Updates the adjacency locally (WorkMesh::replace_faces).
/// \return the path as a chain of vertex ids.
/// \throw InternalError if the path crosses itself inside a face.
std::vector<int> insert_path(WorkMesh& mesh, const std::vector<PathNode>& nodes);

/// Inserts a vertex at barycentric coordinates `bary` of face `f` (splitting the face, or the
/// edge when one coordinate is 0). Returns the new vertex. Updates the adjacency locally.
int insert_point(WorkMesh& mesh, int f, const Vec3& bary);

}  // namespace ctmap
