#include "ctmap/cut/chart_regions.h"

#include <algorithm>
#include <exception>
#include <map>
#include <set>

#include "ctmap/cut/seam_guide.h"
#include "ctmap/cut/seam_homology.h"
#include "ctmap/cut/seam_paths.h"
#include "ctmap/cut/seam_sides.h"
#include "ctmap/cut/work_mesh.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

/// Every chart's border traced as seam pieces, each pair of consecutive border features once
/// (by the first chart that lists it): along the mesh border where both lie on it with no other
/// feature between them, else a shortest path (with `weight`, if given).
SeamLayout trace_seams(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                       const std::vector<double>* weight) {
    SeamLayout layout;
    layout.blocked.assign(mesh.num_vertices(), 0);
    for (const ChartOutline& c : charts) {
        for (int v : c.border) layout.blocked[v] = 1;
        for (int v : c.interior) layout.blocked[v] = 1;
    }
    std::map<std::uint64_t, int> piece_of;  // undirected feature pair -> seam index
    layout.chart_pieces.resize(charts.size());
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const ChartOutline& ch = charts[c];
        for (std::size_t i = 0; i < ch.border.size(); ++i) {
            const int a = ch.border[i], b = ch.border[(i + 1) % ch.border.size()];
            auto it = piece_of.find(edge_key(a, b));
            if (it == piece_of.end()) {
                std::vector<int> path;
                if (graph.on_border[a] && graph.on_border[b]) path = border_arc(mesh, graph, a, b, layout.blocked);
                const bool movable = path.empty();
                if (movable) path = seam_shortest_path(mesh, graph, a, b, layout.blocked, layout.seam_edges, weight);
                if (path.empty())
                    throw BadInput("", "chart " + quoted_name(ch.name) + ": no seam joins its border features " +
                                           quoted_name(ch.border_names[i]) + " and " +
                                           quoted_name(ch.border_names[(i + 1) % ch.border.size()]) +
                                           " without touching another feature or seam (move one, or list the border "
                                           "in another order)");
                for (std::size_t k = 1; k + 1 < path.size(); ++k) layout.blocked[path[k]] = 1;
                for (std::size_t k = 0; k + 1 < path.size(); ++k) layout.seam_edges.insert(edge_key(path[k], path[k + 1]));
                it = piece_of.emplace(edge_key(a, b), int(layout.pieces.size())).first;
                layout.pieces.push_back(std::move(path));
                layout.movable.push_back(movable);
            }
            layout.chart_pieces[c].push_back({it->second, layout.pieces[it->second].front() == a});
        }
    }
    return layout;
}

/// The cyclic order of `names` restricted to `common`, starting at its smallest name.
std::vector<std::string> cyclic(const std::vector<std::string>& names, const std::set<std::string>& common) {
    std::vector<std::string> out;
    for (const std::string& n : names)
        if (common.count(n)) out.push_back(n);
    if (!out.empty()) std::rotate(out.begin(), std::min_element(out.begin(), out.end()), out.end());
    return out;
}

/// The regions of the seams of `layout`: each chart's side of its loop, checked to be a disc
/// bounded by the loop that holds exactly the chart's interior features.
/// \throw BadInput naming the chart when its loop gives it no side, or its side is no such disc.
ChartRegions regions_of(const TriMesh& mesh, const SeamGraph& graph, const std::vector<ChartOutline>& charts,
                        const SeamLayout& layout, const std::map<int, std::string>& feature_name) {
    const int nv = mesh.num_vertices(), nf = mesh.num_faces();
    ChartRegions out;
    const ChartSides sides = chart_sides(mesh, graph, charts, layout);
    if (!sides.error.empty()) throw BadInput("", sides.error);
    out.seams = layout.pieces;
    out.rerouted = int(layout.rerouted.size());
    std::vector<std::vector<int>> loops(charts.size());
    for (std::size_t c = 0; c < charts.size(); ++c) loops[c] = chart_loop(layout, int(c));
    std::vector<int> chart_of_component(sides.components, -1);
    for (std::size_t c = 0; c < charts.size(); ++c) chart_of_component[sides.side[c]] = int(c);
    out.face_chart.assign(nf, -1);
    const std::vector<int>& component = sides.component;
    for (int f = 0; f < nf; ++f) out.face_chart[f] = chart_of_component[component[f]];

    // Each region as a mesh of its own; a disc bounded by its chart's loop, holding exactly the
    // chart's interior features.
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const ChartOutline& ch = charts[c];
        ChartRegion r;
        std::vector<int> local(nv, -1);
        for (int f = 0; f < nf; ++f)
            if (out.face_chart[f] == int(c))
                for (int v : mesh.faces[f]) local[v] = 0;
        for (int v = 0; v < nv; ++v)
            if (local[v] == 0) local[v] = int(r.global.size()), r.global.push_back(v), r.mesh.positions.push_back(mesh.positions[v]);
        for (int f = 0; f < nf; ++f)
            if (out.face_chart[f] == int(c)) {
                r.faces.push_back(f);
                r.mesh.faces.push_back({local[mesh.faces[f][0]], local[mesh.faces[f][1]], local[mesh.faces[f][2]]});
            }
        const MeshTopology topo = compute_topology(r.mesh);
        std::set<int> loop_vertices(loops[c].begin(), loops[c].end());
        const bool bounded = topo.is_disc && topo.border_edges == int(loops[c].size());
        if (!bounded)
            throw BadInput("", "chart " + quoted_name(ch.name) + ": its region of the mesh is not a disc bounded by its border (" +
                                   std::to_string(topo.border_loops) + " border loops, Euler characteristic " +
                                   std::to_string(topo.euler) +
                                   "): on a mesh with handles or holes, the border must go round a disc");
        for (std::size_t i = 0; i < ch.interior.size(); ++i)
            if (local[ch.interior[i]] < 0 || loop_vertices.count(ch.interior[i]))
                throw BadInput("", "chart " + quoted_name(ch.name) + ": its feature " + quoted_name(ch.interior_names[i]) +
                                       " lies outside its region of the mesh: move it, or the border");
        std::set<int> own(ch.interior.begin(), ch.interior.end());
        std::vector<std::string> foreign;
        for (const auto& [v, name] : feature_name)
            if (local[v] >= 0 && !loop_vertices.count(v) && !own.count(v)) foreign.push_back(name);
        if (!foreign.empty()) {
            std::string list;
            for (const auto& n : foreign) list += (list.empty() ? "" : ", ") + quoted_name(n);
            throw BadInput("", "chart " + quoted_name(ch.name) + ": its region of the mesh holds features of other charts (" +
                                   list + "): list them in this chart too, or move the border");
        }
        out.charts.push_back(std::move(r));
    }
    return out;
}

/// One attempt: the seams traced (with `weight`, if given), re-routed off the handles and round
/// misplaced features, and the regions they give. \throw BadInput as `chart_regions`.
ChartRegions attempt(const TriMesh& mesh, const SeamGraph& graph, const HandleLoops& handles,
                     const std::vector<ChartOutline>& charts, const std::vector<double>* weight,
                     const std::map<int, std::string>& feature_name) {
    SeamLayout layout = trace_seams(mesh, graph, charts, weight);
    // Off the handles, then round the features; a piece re-routed round a feature may have
    // taken a handle's short way, so a few rounds.
    for (int round = 0; round < 4; ++round) {
        if (keep_seams_off_handles(mesh, graph, handles, charts, layout, weight) == 0 && round > 0) break;
        keep_features_on_their_sides(mesh, graph, charts, layout, &handles);
    }
    if (weight)  // every piece through the interior was traced by the guide
        for (std::size_t k = 0; k < layout.pieces.size(); ++k)
            if (layout.movable[k]) layout.rerouted.insert(int(k));
    return regions_of(mesh, graph, charts, layout, feature_name);
}

}  // namespace

ChartRegions chart_regions(const TriMesh& mesh, const std::vector<ChartOutline>& charts) {
    const int nv = mesh.num_vertices();
    for (const ChartOutline& c : charts) {
        if (c.border.size() < 3)
            throw BadInput("", "chart " + quoted_name(c.name) + ": its border needs at least 3 features");
        for (int v : c.border)
            if (v < 0 || v >= nv) throw BadInput("", "chart " + quoted_name(c.name) + ": border vertex out of range");
        for (int v : c.interior)
            if (v < 0 || v >= nv) throw BadInput("", "chart " + quoted_name(c.name) + ": feature vertex out of range");
    }
    // Two charts with the same border features (two sides of a closed mesh) go round them in
    // one cyclic order, in either direction.
    for (std::size_t i = 0; i < charts.size(); ++i)
        for (std::size_t j = 0; j < i; ++j) {
            std::set<std::string> a(charts[i].border_names.begin(), charts[i].border_names.end()), common;
            for (const std::string& n : charts[j].border_names)
                if (a.count(n)) common.insert(n);
            if (common.size() < 3) continue;
            const std::vector<std::string> x = cyclic(charts[i].border_names, common);
            std::vector<std::string> y = cyclic(charts[j].border_names, common), y_back(y.rbegin(), y.rend());
            std::rotate(y_back.begin(), std::min_element(y_back.begin(), y_back.end()), y_back.end());
            if (x != y && x != y_back) {
                std::string list_x, list_y;
                for (const auto& n : x) list_x += (list_x.empty() ? "" : ", ") + n;
                for (const auto& n : y) list_y += (list_y.empty() ? "" : ", ") + n;
                throw BadInput("", "charts " + quoted_name(charts[j].name) + " and " + quoted_name(charts[i].name) +
                                       " go round their common border features in different orders (" + list_y +
                                       " against " + list_x + "): a seam is one line on the mesh, so list them in "
                                       "one cyclic order (either direction)");
            }
        }

    // A chart's interior feature may not be another chart's border feature (it would lie on a
    // seam, on no one side).
    std::map<int, std::pair<std::string, std::string>> border_of;  // vertex -> (feature, chart)
    for (const ChartOutline& c : charts)
        for (std::size_t i = 0; i < c.border.size(); ++i) border_of.emplace(c.border[i], std::make_pair(c.border_names[i], c.name));
    for (const ChartOutline& c : charts)
        for (std::size_t i = 0; i < c.interior.size(); ++i)
            if (const auto it = border_of.find(c.interior[i]); it != border_of.end())
                throw BadInput("", "feature " + quoted_name(c.interior_names[i]) + " is inside chart " + quoted_name(c.name) +
                                       " but on the border of chart " + quoted_name(it->second.second) +
                                       ": a feature on a seam is a border feature of every chart it is in");
    const SeamGraph graph(mesh);
    const HandleLoops handles = handle_loops(mesh, graph);
    std::map<int, std::string> feature_name;
    for (const ChartOutline& c : charts) {
        for (std::size_t i = 0; i < c.border.size(); ++i) feature_name[c.border[i]] = c.border_names[i];
        for (std::size_t i = 0; i < c.interior.size(); ++i) feature_name[c.interior[i]] = c.interior_names[i];
    }
    // The shortest seams; where they leave a feature outside its chart, pieces are traced again
    // round it. If that gives no seams or no discs, the same from seams drawn to where the charts'
    // regions, grown from their features, meet; the first attempt's error is the one reported.
    try {
        return attempt(mesh, graph, handles, charts, nullptr, feature_name);
    } catch (const BadInput&) {
        const std::exception_ptr first = std::current_exception();
        std::vector<std::vector<double>> guides;
        for (double strength : {8.0, 64.0}) {
            if (charts.size() == 1) guides.push_back(seam_level_weights(mesh, graph, charts[0], strength));
            guides.push_back(seam_guide_weights(mesh, graph, charts, strength));
        }
        for (const std::vector<double>& weight : guides) {
            if (weight.empty()) continue;
            try {
                return attempt(mesh, graph, handles, charts, &weight, feature_name);
            } catch (const BadInput&) {
            }
        }
        std::rethrow_exception(first);
    }
}

}  // namespace ctmap
