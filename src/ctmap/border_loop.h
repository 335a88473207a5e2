#pragma once
/// \file border_loop.h
/// The border of a disc as one loop of vertices, straight from the face list: the cut's border
/// features and the starter features need only this, and building the cut's whole WorkMesh for
/// it cost most of the triangulation stage on a million triangles.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// The border loop of `mesh` in the faces' orientation (interior on the left), starting at its
/// smallest vertex index; empty for a closed mesh.
/// \pre `mesh` is a consistently oriented manifold disc (one border loop; checked on input by
///      `mesh_topology`).
std::vector<int> border_loop(const TriMesh& mesh);

/// The same for a face list on vertices 0..num_vertices-1 (the cut's WorkMesh uses this).
std::vector<int> border_loop(const std::vector<Tri>& faces, int num_vertices);

}  // namespace ctmap
