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
    /// Overlay the two maps, so that both shapes are reproduced exactly; off: the source's
    /// connectivity only (the target surface only sampled at the source's vertices).
    bool insert_target_vertices = true;
};

/// The common mesh.
struct CommonMesh {
    TriMesh mesh;                     ///< positions on the source surface; faces oriented as the source's
    std::vector<Vec3> target_position;  ///< per vertex, its point on the target surface
    std::vector<Vec2> uv;             ///< per vertex, its point in the shared domain
    int source_vertices = 0;          ///< vertices [0, source_vertices) are the source map's, in order
    int inserted = 0;                 ///< target vertices added (after the source's)
    int merged = 0;                   ///< target vertices at exactly a source vertex's point (shared)
    int crossings = 0;                ///< vertices where a source edge crosses a target edge (added last)
    int outside = 0;                  ///< points found outside the other map by rounding (snapped to it)
};

/// Builds the common mesh of two maps into one domain: the overlay of the two triangulations (a
/// constrained Delaunay triangulation of both maps' vertices and edges, CGAL, exact intersections),
/// so that each of its triangles lies inside one source and one target triangle and is flat on
/// both surfaces. Its vertices are the source's (first, in order), then the target's not shared
/// with a source vertex, then the edge crossings. Each vertex takes its point on the other surface
/// where its UV lies in the other map (grid point location, exact orientation tests); a vertex of
/// a map keeps its exact position on that map's surface.
/// \pre both maps valid (one orientation, no overlap) over the same domain; in particular, the
///      source's border lies on the target's (rounding aside).
CommonMesh common_mesh(const PlanarMap& source, const PlanarMap& target, const CommonMeshOptions& options = {});

}  // namespace ctmap
