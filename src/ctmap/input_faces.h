#pragma once
/// \file input_faces.h
/// Which input face each face of a map lies in (issue 42: the bake's exact transfer onto the
/// mesh the map was computed from). The cut only ever splits the input's triangles (paper §2.3:
/// paths and Steiner points are inserted on the surface, never moved off it), so every face of
/// the map lies inside one input face, and its centroid lies strictly inside that face: the input
/// face closest to the centroid is the one it came from.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Per face of `refined`, the face of `input` it lies in.
/// \pre `refined`'s faces lie on `input`'s surface (a map of `input`: map_texture, map_charts),
///      and `input` has a face of nonzero area. \throw BadInput otherwise (no face of nonzero area).
std::vector<int> input_faces_of(const TriMesh& input, const TriMesh& refined);

}  // namespace ctmap
