#pragma once
/// \file common_mesh.h
/// The mesh both shapes share (paper §4, issue 14): the source's mesh, refined where the target has
/// detail, with every vertex placed on both surfaces through the two maps into one domain.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// A planar map of a mesh: the mesh and one UV per vertex (a valid map: certified).
struct PlanarMap {
    const TriMesh* mesh = nullptr;
    const std::vector<Vec2>* uv = nullptr;
};

/// Options of `common_mesh`.
struct CommonMeshOptions {
    /// Insert every target vertex into the source's faces (the overlay's vertices), so that the
    /// morphed surface holds all of the target's vertices; off: the source's connectivity only.
    bool insert_target_vertices = true;
};

/// The common mesh.
struct CommonMesh {
    TriMesh mesh;                     ///< positions on the source surface; faces oriented as the source's
    std::vector<Vec3> target_position;  ///< per vertex, its point on the target surface
    std::vector<Vec2> uv;             ///< per vertex, its point in the shared domain
    int source_vertices = 0;          ///< vertices [0, source_vertices) are the source map's, in order
    int inserted = 0;                 ///< target vertices inserted into source faces
    int merged = 0;                   ///< target vertices at exactly a source vertex's point (shared)
    int outside = 0;                  ///< points found outside the other map by rounding (snapped to it)
};

/// Builds the common mesh of two maps into one domain: every source vertex takes the target
/// surface point found where its UV lies in the target's map (grid point location, exact
/// orientation tests); every target vertex is inserted where its UV lies in the source's map (a
/// face or an edge split; a Delaunay triangulation of each split face in its own barycentric
/// frame, with exact predicates) and takes its exact target position. A source vertex whose UV
/// is exactly a target vertex's takes that vertex's exact position.
/// \pre both maps valid (one orientation, no overlap) over the same domain; in particular, the
///      source's border lies on the target's (rounding aside).
CommonMesh common_mesh(const PlanarMap& source, const PlanarMap& target, const CommonMeshOptions& options = {});

}  // namespace ctmap
