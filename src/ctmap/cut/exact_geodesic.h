#pragma once
/// \file exact_geodesic.h
/// Exact geodesics on a triangle mesh (CGAL `Surface_mesh_shortest_path`, Xin & Wang's variant
/// of Chen & Han): the oracle the approximate paths are measured against (issue 3, must-show 2),
/// and the paths of `CutOptions::exact_geodesics`. CGAL stays inside exact_geodesic.cpp.
#include <memory>
#include <optional>
#include <vector>

#include "ctmap/cut/approximate_path.h"
#include "ctmap/cut/insert_path.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Exact geodesic distances and paths from one source vertex; the sequence tree is built once
/// per source and reused for every target (one tree costs about as much as the mesh is large,
/// squared at worst).
class ExactGeodesic {
public:
    /// \pre `faces` is a consistently oriented, connected manifold triangle mesh on `positions`.
    ExactGeodesic(const std::vector<Vec3>& positions, const std::vector<Tri>& faces);
    ~ExactGeodesic();
    ExactGeodesic(const ExactGeodesic&) = delete;
    ExactGeodesic& operator=(const ExactGeodesic&) = delete;

    /// Sets the source vertex (builds its sequence tree). \pre 0 <= vertex < number of vertices.
    void set_source(int vertex);
    /// The geodesic distance from the source to `vertex` (-1 if unreachable).
    double distance(int vertex);
    /// The geodesic from the source to `vertex` as nodes: the source vertex first, then every
    /// vertex passed through and every edge crossed (PathNode::a/b/t), the target last. The
    /// `face` fields are left at -1: the caller knows its mesh's faces. Empty if unreachable.
    std::vector<PathNode> path(int vertex);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/// Options of `find_exact_path`.
struct ExactPathOptions {
    /// Edge crossings closer to a free vertex than this fraction of their edge snap to it (no
    /// slivers; the path stays within this fraction of an edge of the geodesic).
    double snap_fraction = 0.02;
};

/// Why `find_exact_path` rejected a geodesic (for statistics).
enum class ExactPathRejection { none, blocked_vertex, crosses_path, sector, degenerate };

/// The exact geodesic from `c.source` to `c.target` on the current work mesh, as a path for
/// `insert_path`, if it respects the same rules as `find_path` (DESIGN §2 conditions 1-2): it
/// passes through no blocked vertex, crosses no path or border edge, and leaves and enters its
/// ends inside their sectors. The geodesic is computed on the whole surface, blind to paths; a
/// caller falls back to `find_path` when it is rejected (`why` says why).
/// \pre source != target, both vertices of `mesh`.
std::optional<FoundPath> find_exact_path(const WorkMesh& mesh, const PathConstraints& c,
                                         const ExactPathOptions& opt = {}, ExactPathRejection* why = nullptr);

}  // namespace ctmap
