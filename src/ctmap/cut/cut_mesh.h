#pragma once
/// \file cut_mesh.h
/// The result of the cut (paper §2.3, Table 1): the mesh refined so that every edge of the
/// feature triangulation is a chain of mesh edges, and the faces grouped into one patch per image
/// triangle. This is what the embedding (paper §2.4) consumes.
#include <array>
#include <vector>

#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// One patch: the faces mapped into one triangle of the feature triangulation.
struct Patch {
    Tri corners;  ///< feature indices, in the order of the image triangle (counter-clockwise)
    /// sides[k]: mesh vertex chain from the vertex of corners[k] to the vertex of corners[(k+1)%3],
    /// both ends included. The patch lies on the left of each side (the mesh's orientation).
    std::array<std::vector<int>, 3> sides;
};

/// The cut mesh.
struct CutMesh {
    /// Refined mesh: vertices [0, num_input_vertices) are the input's, same order and position;
    /// inserted vertices follow and lie on the input surface. Faces are new.
    TriMesh mesh;
    int num_input_vertices = 0;
    std::vector<int> feature_vertex;  ///< per feature, its vertex in `mesh`
    std::vector<int> face_patch;      ///< per face of `mesh`, its patch (= image triangle index)
    std::vector<Patch> patches;       ///< one per triangle of the feature triangulation, same index
    /// Per vertex of `mesh`: the input face it lies in (barycentric coordinates in `vertex_bary`),
    /// so UVs can be carried back to the input surface. Input vertices: any incident face.
    std::vector<int> vertex_face;
    std::vector<Vec3> vertex_bary;
    int steiner_vertices = 0;  ///< vertices added by the fallback (condition 4), not on paths
};

}  // namespace ctmap
