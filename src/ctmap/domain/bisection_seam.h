#pragma once
/// \file bisection_seam.h
/// Seam features for a closed mesh cut in two (paper §3: Igea's two photos meet on its
/// "bisection line"): vertices around the plane through the mesh's centre, in order round it.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// `count` vertices near the plane through the bounding box's centre whose normal is the box's
/// shortest axis (left and right halves of a head or an animal), one per equal angle round the
/// centre in that plane (the farthest vertex from the centre in that direction), counter-clockwise
/// about the axis, without repeats.
/// \pre count >= 3; `mesh` has faces. \throw BadInput if fewer than 3 distinct vertices are found.
std::vector<int> bisection_seam_vertices(const TriMesh& mesh, int count);

}  // namespace ctmap
