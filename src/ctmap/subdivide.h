#pragma once
/// \file subdivide.h
/// 1-to-4 midpoint subdivision, for the scaling benchmarks (issue 6): every triangle split into
/// four at its edge midpoints, so the surface keeps its shape exactly (the new vertices lie on
/// the old edges) while the triangle count grows by 4 per level.
#include "ctmap/mesh.h"

namespace ctmap {

/// Subdivides `mesh` `levels` times. The input's vertices keep their indices (DESIGN §3); each
/// level appends one vertex per edge. Faces keep their orientation.
/// \pre levels >= 0; `mesh` has no face with a repeated corner.
TriMesh subdivide_midpoint(const TriMesh& mesh, int levels);

}  // namespace ctmap
