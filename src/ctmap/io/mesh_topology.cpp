#include "ctmap/io/mesh_topology.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "ctmap/edge_key.h"
#include "ctmap/errors.h"
#include "ctmap/union_find.h"

namespace ctmap {
namespace {

bool is_degenerate(const TriMesh& m, const Tri& t) {
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    auto P = [&](int i) { return K::Point_3(m.positions[i].x(), m.positions[i].y(), m.positions[i].z()); };
    return CGAL::collinear(P(t[0]), P(t[1]), P(t[2]));
}

struct PositionHash {
    std::size_t operator()(const Vec3& p) const {
        std::hash<double> h;
        return h(p.x()) ^ (h(p.y()) * 31) ^ (h(p.z()) * 1009);
    }
};
struct PositionEq {
    bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
};

}  // namespace

MeshTopology compute_topology(const TriMesh& mesh) {
    MeshTopology t;
    const int nv = mesh.num_vertices();
    const int nf = mesh.num_faces();
    t.vertices = nv;
    t.faces = nf;

    // Edge -> incident faces, and whether the edge is traversed a->b (with a<b) in that face.
    struct EdgeUse {
        int count = 0;
        int forward = 0;  // faces that traverse it from the smaller to the larger index
    };
    std::unordered_map<std::uint64_t, EdgeUse> edges;
    edges.reserve(std::size_t(nf) * 2);
    std::vector<std::vector<int>> vertex_faces(nv);
    std::vector<char> used(nv, 0);
    for (int f = 0; f < nf; ++f) {
        const Tri& tri = mesh.faces[f];
        if (is_degenerate(mesh, tri)) ++t.degenerate_faces;
        for (int k = 0; k < 3; ++k) {
            const int a = tri[k], b = tri[(k + 1) % 3];
            used[a] = 1;
            if (a == b) continue;
            EdgeUse& e = edges[edge_key(a, b)];
            ++e.count;
            if (a < b) ++e.forward;
        }
        for (int k = 0; k < 3; ++k)
            if (std::find(tri.begin(), tri.begin() + k, tri[k]) == tri.begin() + k)
                vertex_faces[tri[k]].push_back(f);
    }
    t.edges = int(edges.size());
    t.euler = t.vertices - t.edges + t.faces;
    t.isolated_vertices = int(std::count(used.begin(), used.end(), 0));

    UnionFind border(nv);
    std::unordered_set<int> border_vertices;
    for (const auto& [key, use] : edges) {
        const int a = int(key >> 32), b = int(key & 0xffffffffu);
        if (use.count == 1) {
            ++t.border_edges;
            border.unite(a, b);
            border_vertices.insert(a);
            border_vertices.insert(b);
        } else if (use.count > 2) {
            ++t.non_manifold_edges;
        } else if (use.forward != 1) {
            ++t.inconsistent_edges;
        }
    }
    std::unordered_set<int> loop_roots;
    for (int v : border_vertices) loop_roots.insert(border.find(v));
    t.border_loops = int(loop_roots.size());

    // Components of faces: faces joined through shared vertices.
    UnionFind comp(nv);
    for (const Tri& tri : mesh.faces) {
        comp.unite(tri[0], tri[1]);
        comp.unite(tri[1], tri[2]);
    }
    std::unordered_set<int> comp_roots;
    for (const Tri& tri : mesh.faces) comp_roots.insert(comp.find(tri[0]));
    t.components = int(comp_roots.size());

    // A vertex is manifold when its faces form one fan: faces joined across manifold edges at v.
    for (int v = 0; v < nv; ++v) {
        const auto& fs = vertex_faces[v];
        if (fs.size() <= 1) continue;
        std::unordered_map<int, std::vector<int>> by_neighbour;  // other edge end -> local faces
        for (int i = 0; i < int(fs.size()); ++i)
            for (int w : mesh.faces[fs[i]])
                if (w != v) by_neighbour[w].push_back(i);
        UnionFind fan(int(fs.size()));
        for (const auto& [w, local] : by_neighbour)
            if (local.size() == 2 && edges[edge_key(v, w)].count == 2) fan.unite(local[0], local[1]);
        int fans = 0;
        for (int i = 0; i < int(fs.size()); ++i) fans += fan.find(i) == i;
        if (fans > 1) ++t.non_manifold_vertices;
    }

    std::unordered_set<Vec3, PositionHash, PositionEq> seen;
    for (const Vec3& p : mesh.positions)
        if (!seen.insert(p).second) ++t.duplicated_vertices;

    t.is_manifold = t.non_manifold_edges == 0 && t.non_manifold_vertices == 0 && t.inconsistent_edges == 0;
    t.is_closed = t.is_manifold && t.border_edges == 0 && t.faces > 0;
    t.is_disc = t.is_manifold && t.components == 1 && t.border_loops == 1 && t.euler == 1 &&
                t.isolated_vertices == 0;
    return t;
}

namespace {

/// What keeps `t` from being a clean manifold (and, with `disc`, a disc), for the messages.
void require(const MeshTopology& t, const std::string& file, bool disc, NotDiscAdvice advice) {
    std::vector<std::string> problems;
    if (t.non_manifold_edges)
        problems.push_back(std::to_string(t.non_manifold_edges) + " non-manifold edge(s) (more than two faces)");
    if (t.non_manifold_vertices)
        problems.push_back(std::to_string(t.non_manifold_vertices) + " non-manifold vertex(es) (faces meet at a point)");
    if (t.inconsistent_edges)
        problems.push_back(std::to_string(t.inconsistent_edges) + " edge(s) between oppositely oriented faces");
    if (disc) {
        const bool charts = advice == NotDiscAdvice::charts;
        if (t.components != 1) problems.push_back(std::to_string(t.components) + " connected components (need 1)");
        if (t.border_loops == 0)
            problems.push_back(charts ? "no border: the mesh is closed and needs seams (a features file with charts, "
                                        "README \"Charts\"; or cut it open first)"
                                      : "no border: the mesh is closed (this command takes one chart, a disc: cut it "
                                        "open first, or map it with charts by `ctmap map`)");
        else if (t.border_loops > 1)
            problems.push_back(std::to_string(t.border_loops) +
                               (charts ? " border loops (a disc has 1; give a features file with charts, or fill the holes)"
                                       : " border loops (a disc has 1; this command takes one chart: fill the holes, or "
                                         "map it with charts by `ctmap map`)"));
        if (problems.empty() && t.euler != 1)
            problems.push_back("Euler characteristic " + std::to_string(t.euler) +
                               (charts ? " (a disc has 1: the mesh has handles; give a features file with charts)"
                                       : " (a disc has 1: the mesh has handles; this command takes one chart: map it "
                                         "with charts by `ctmap map`)"));
    }
    if (t.isolated_vertices) problems.push_back(std::to_string(t.isolated_vertices) + " isolated vertex(es) used by no face");
    if (t.degenerate_faces) problems.push_back(std::to_string(t.degenerate_faces) + " degenerate face(s) (zero area)");
    if (problems.empty()) return;
    std::string msg = disc ? "the mesh is not a clean topological disc: " : "the mesh is not a clean oriented manifold: ";
    for (std::size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    throw TopologyError(file, msg);
}

}  // namespace

void require_disc(const MeshTopology& t, const std::string& file, NotDiscAdvice advice) {
    require(t, file, true, advice);
}

void require_manifold(const MeshTopology& t, const std::string& file) { require(t, file, false, NotDiscAdvice::charts); }

std::string topology_to_json(const MeshTopology& t) {
    nlohmann::ordered_json j;
    j["vertices"] = t.vertices;
    j["faces"] = t.faces;
    j["edges"] = t.edges;
    j["components"] = t.components;
    j["border_loops"] = t.border_loops;
    j["border_edges"] = t.border_edges;
    j["euler"] = t.euler;
    j["non_manifold_vertices"] = t.non_manifold_vertices;
    j["non_manifold_edges"] = t.non_manifold_edges;
    j["inconsistent_edges"] = t.inconsistent_edges;
    j["degenerate_faces"] = t.degenerate_faces;
    j["duplicated_vertices"] = t.duplicated_vertices;
    j["isolated_vertices"] = t.isolated_vertices;
    j["is_manifold"] = t.is_manifold;
    j["is_disc"] = t.is_disc;
    j["is_closed"] = t.is_closed;
    return j.dump(2);
}

}  // namespace ctmap
