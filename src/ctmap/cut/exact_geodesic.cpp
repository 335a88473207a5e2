#include "ctmap/cut/exact_geodesic.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<K, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;

/// Collects CGAL's path sequence (from the query back to the source) as PathNodes.
struct NodeCollector {
    const SurfaceMesh& mesh;
    std::vector<PathNode>& out;
    void operator()(SurfaceMesh::Halfedge_index h, double t) {
        // CGAL's point(h, t) is source(h) + t (target(h) - source(h)).
        PathNode n;
        n.a = int(mesh.source(h));
        n.b = int(mesh.target(h));
        n.t = t;
        out.push_back(n);
    }
    void operator()(SurfaceMesh::Vertex_index v) {
        PathNode n;
        n.vertex = int(v);
        out.push_back(n);
    }
    template <class Bary>
    void operator()(SurfaceMesh::Face_index, const Bary&) {}  // the source point itself
};


}  // namespace

struct ExactGeodesic::Impl {
    SurfaceMesh mesh;
    std::unique_ptr<ShortestPath> sp;
    int source = -1;
};

ExactGeodesic::ExactGeodesic(const std::vector<Vec3>& positions, const std::vector<Tri>& faces)
    : impl_(std::make_unique<Impl>()) {
    SurfaceMesh& m = impl_->mesh;
    m.reserve(SurfaceMesh::size_type(positions.size()), SurfaceMesh::size_type(3 * faces.size()),
              SurfaceMesh::size_type(faces.size()));
    for (const Vec3& p : positions) m.add_vertex(K::Point_3(p.x(), p.y(), p.z()));
    for (const Tri& t : faces)
        if (m.add_face(SurfaceMesh::Vertex_index(t[0]), SurfaceMesh::Vertex_index(t[1]),
                       SurfaceMesh::Vertex_index(t[2])) == SurfaceMesh::null_face())
            throw InternalError("exact geodesic: the mesh is not a consistently oriented manifold");
    impl_->sp = std::make_unique<ShortestPath>(m);
}

ExactGeodesic::~ExactGeodesic() = default;

void ExactGeodesic::set_source(int vertex) {
    ShortestPath& sp = *impl_->sp;
    sp.remove_all_source_points();
    sp.add_source_point(SurfaceMesh::Vertex_index(vertex));
    sp.build_sequence_tree();
    impl_->source = vertex;
}

double ExactGeodesic::distance(int vertex) {
    return impl_->sp->shortest_distance_to_source_points(SurfaceMesh::Vertex_index(vertex)).first;
}

std::vector<PathNode> ExactGeodesic::path(int vertex) {
    std::vector<PathNode> nodes;
    NodeCollector collect{impl_->mesh, nodes};
    impl_->sp->shortest_path_sequence_to_source_points(SurfaceMesh::Vertex_index(vertex), collect);
    if (nodes.empty()) return nodes;
    std::reverse(nodes.begin(), nodes.end());
    // The source is reported as a face location: put it back as the vertex it is.
    if (nodes.front().vertex != impl_->source) {
        PathNode s;
        s.vertex = impl_->source;
        nodes.insert(nodes.begin(), s);
    }
    return nodes;
}

std::optional<FoundPath> find_exact_path(const WorkMesh& mesh, const PathConstraints& c, const ExactPathOptions& opt,
                                         ExactPathRejection* why) {
    auto reject = [&](ExactPathRejection r) -> std::optional<FoundPath> {
        if (why) *why = r;
        return std::nullopt;
    };
    if (why) *why = ExactPathRejection::none;
    auto is_free = [&](int v) { return v == c.source || v == c.target || !(*c.blocked)[v]; };

    ExactGeodesic geodesic(mesh.positions, mesh.faces);
    geodesic.set_source(c.source);
    std::vector<PathNode> raw = geodesic.path(c.target);
    if (raw.size() < 2 || raw.front().vertex != c.source || raw.back().vertex != c.target)
        return reject(ExactPathRejection::degenerate);

    // Crossings very near a vertex: snap to it when the path may use it, else keep them that far
    // from it (a path may pass a blocked vertex, not touch it). Either way no sliver is made, and
    // the nodes stay on the same edges, so consecutive nodes still share a face.
    std::vector<PathNode> nodes;
    for (PathNode n : raw) {
        if (n.vertex < 0) {
            const double s = std::min(n.t, 1 - n.t);
            const int near = n.t < 0.5 ? n.a : n.b;
            if (s < opt.snap_fraction) {
                if (is_free(near)) {
                    n = PathNode{};
                    n.vertex = near;
                } else {
                    n.t = n.t < 0.5 ? opt.snap_fraction : 1 - opt.snap_fraction;
                }
            }
        }
        nodes.push_back(n);
    }
    // A vertex met twice (snapping can do it): drop the loop between.
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].vertex < 0) continue;
        std::size_t last = i;
        for (std::size_t j = i + 1; j < nodes.size(); ++j)
            if (nodes[j].vertex == nodes[i].vertex) last = j;
        nodes.erase(nodes.begin() + i + 1, nodes.begin() + last + 1);
    }
    // Faces a node lies in.
    auto faces_of = [&](const PathNode& n) -> std::vector<int> {
        if (n.vertex >= 0) return mesh.vertex_faces[n.vertex];
        const int e = mesh.find_edge(n.a, n.b);
        if (e < 0) return {};
        std::vector<int> out;
        for (int f : mesh.edge_faces[e])
            if (f >= 0) out.push_back(f);
        return out;
    };
    auto on_edge_of = [](const PathNode& n, int v) { return n.vertex < 0 && (n.a == v || n.b == v); };
    auto common_face = [&](const PathNode& p, const PathNode& q) {
        const auto fp = faces_of(p), fq = faces_of(q);
        for (int f : fp)
            if (contains(fq, f)) return f;
        return -1;
    };
    // A crossing on an edge of the vertex just before or after it runs along that edge: skip it
    // when its neighbours still share a face (a straight cut through that face instead).
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t i = 1; i + 1 < nodes.size(); ++i) {
            const PathNode &p = nodes[i - 1], &n = nodes[i], &q = nodes[i + 1];
            if (((p.vertex >= 0 && on_edge_of(n, p.vertex)) || (q.vertex >= 0 && on_edge_of(n, q.vertex))) &&
                common_face(p, q) >= 0) {
                nodes.erase(nodes.begin() + i);
                changed = true;
                break;
            }
        }
    }

    FoundPath out;
    out.nodes = nodes;
    auto position = [&](const PathNode& n) -> Vec3 {
        if (n.vertex >= 0) return mesh.positions[n.vertex];
        return mesh.positions[n.a] + n.t * (mesh.positions[n.b] - mesh.positions[n.a]);
    };
    const std::size_t last = out.nodes.size() - 1;
    for (std::size_t i = 0; i <= last; ++i) {
        PathNode& n = out.nodes[i];
        if (n.vertex >= 0) {
            if (i > 0 && i < last && !is_free(n.vertex)) return reject(ExactPathRejection::blocked_vertex);
        } else {
            const int e = mesh.find_edge(n.a, n.b);
            if (e < 0) return reject(ExactPathRejection::degenerate);
            if (mesh.is_border_edge(e) || c.path_edges->count(mesh.edges[e])) return reject(ExactPathRejection::crosses_path);
        }
        if (i == 0) continue;
        const PathNode& p = out.nodes[i - 1];
        out.length += (position(n) - position(p)).norm();
        if (p.vertex >= 0 && n.vertex >= 0) {
            // Two vertices: the path runs along their edge.
            const int e = mesh.find_edge(p.vertex, n.vertex);
            if (e < 0) return reject(ExactPathRejection::degenerate);
            if (c.path_edges->count(mesh.edges[e])) return reject(ExactPathRejection::crosses_path);
            n.face = -1;
        } else {
            if (p.vertex < 0 && n.vertex < 0 && edge_key(p.a, p.b) == edge_key(n.a, n.b))
                return reject(ExactPathRejection::degenerate);
            // Through a face: at the ends prefer one inside the sector.
            const auto fp = faces_of(p), fn = faces_of(n);
            const std::vector<int>* prefer = i == 1 ? &c.source_sector.faces : i == last ? &c.target_sector.faces : nullptr;
            n.face = -1;
            for (int f : fp)
                if (contains(fn, f) && (n.face < 0 || (prefer && contains(*prefer, f)))) n.face = f;
            if (n.face < 0) return reject(ExactPathRejection::degenerate);
        }
    }
    // Sectors (condition 2) on the first and last step.
    auto in_sector = [](const EndSector& s, const PathNode& step, int other_vertex) {
        return step.face >= 0 ? contains(s.faces, step.face) : contains(s.edge_neighbours, other_vertex);
    };
    if (!in_sector(c.source_sector, out.nodes[1], out.nodes[1].vertex) ||
        !in_sector(c.target_sector, out.nodes[last], out.nodes[last - 1].vertex))
        return reject(ExactPathRejection::sector);
    return out;
}

}  // namespace ctmap
