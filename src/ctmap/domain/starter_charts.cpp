#include "ctmap/domain/starter_charts.h"

#include <nlohmann/json.hpp>

#include "ctmap/cut/chart_regions.h"
#include "ctmap/domain/bisection_seam.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace ctmap {

std::vector<ChartFeatures> starter_charts(const TriMesh& mesh, int width, int height, const StarterChartsOptions& opt) {
    const std::vector<int> seam = bisection_seam_vertices(mesh, opt.seam);
    std::vector<ChartOutline> outlines(2);
    for (int c = 0; c < 2; ++c) {
        outlines[c].name = c == 0 ? "front" : "back";
        outlines[c].border = seam;
        for (std::size_t i = 0; i < seam.size(); ++i) outlines[c].border_names.push_back("seam" + std::to_string(i));
        outlines[c].image_ccw = c == 0;  // the left side of the seam, then the right
    }
    const ChartRegions regions = chart_regions(mesh, outlines);
    std::vector<ChartFeatures> out;
    for (int c = 0; c < 2; ++c) {
        const ChartRegion& r = regions.charts[c];
        std::vector<int> local(mesh.num_vertices(), -1);
        for (std::size_t v = 0; v < r.global.size(); ++v) local[r.global[v]] = int(v);
        std::vector<int> border;
        for (int v : seam) border.push_back(local[v]);
        StarterOptions so;
        so.interior = opt.interior;
        so.margin = opt.margin;
        const FeatureSet half = starter_features(r.mesh, width, height, so, &border);
        ChartFeatures cf;
        cf.name = outlines[c].name;
        cf.features.image_size = std::array<int, 2>{width, height};
        for (const Feature& f : half.features) {
            Feature g = f;
            g.vertex = r.global[f.vertex];
            const bool on_seam = f.name.rfind("border", 0) == 0;
            g.name = on_seam ? "seam" + f.name.substr(6) : cf.name + "_" + f.name;
            if (c == 1 && opt.mirror) g.image.x() = width - g.image.x();
            cf.features.features.push_back(g);
        }
        for (std::size_t i = 0; i < seam.size(); ++i) cf.border.push_back("seam" + std::to_string(i));
        out.push_back(std::move(cf));
    }
    return out;
}

ChartFeatures starter_patch_chart(const TriMesh& mesh, int width, int height, double area_share,
                                  const StarterOptions& options) {
    if (!(area_share > 0 && area_share < 1)) throw BadInput("", "the patch's share of the area must lie in (0, 1)");
    const int nv = mesh.num_vertices();
    int seed = 0;
    for (int v = 1; v < nv; ++v)
        if (mesh.positions[v].z() > mesh.positions[seed].z()) seed = v;
    // Distances along edges from the seed (Dijkstra).
    std::vector<std::vector<int>> neighbours(nv);
    for (const Tri& t : mesh.faces)
        for (int k = 0; k < 3; ++k) neighbours[t[k]].push_back(t[(k + 1) % 3]), neighbours[t[(k + 1) % 3]].push_back(t[k]);
    std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[seed] = 0;
    queue.push({0, seed});
    while (!queue.empty()) {
        const auto [d, v] = queue.top();
        queue.pop();
        if (d > dist[v]) continue;
        for (int w : neighbours[v])
            if (const double nd = d + (mesh.positions[w] - mesh.positions[v]).norm(); nd < dist[w]) dist[w] = nd, queue.push({nd, w});
    }
    // Faces by their farthest corner; the ball of radius r holds the faces up to r.
    std::vector<std::pair<double, int>> by_reach;
    double total = 0;
    std::vector<double> area(mesh.faces.size());
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Tri& t = mesh.faces[f];
        area[f] = 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
        total += area[f];
        by_reach.push_back({std::max({dist[t[0]], dist[t[1]], dist[t[2]]}), int(f)});
    }
    std::sort(by_reach.begin(), by_reach.end());
    for (double share = area_share; share > 1e-3; share *= 0.8) {
        TriMesh ball;
        std::vector<int> local(nv, -1), global;
        double a = 0;
        for (const auto& [reach, f] : by_reach) {
            if (a >= share * total) break;
            a += area[f];
            Tri t;
            for (int k = 0; k < 3; ++k) {
                int& l = local[mesh.faces[f][k]];
                if (l < 0) l = ball.num_vertices(), global.push_back(mesh.faces[f][k]), ball.positions.push_back(mesh.positions[mesh.faces[f][k]]);
                t[k] = l;
            }
            ball.faces.push_back(t);
        }
        if (!compute_topology(ball).is_disc) continue;
        const FeatureSet fs = starter_features(ball, width, height, options);
        ChartFeatures cf;
        cf.name = "patch";
        cf.features.image_size = std::array<int, 2>{width, height};
        for (const Feature& f : fs.features) {
            Feature g = f;
            g.vertex = global[f.vertex];
            cf.features.features.push_back(g);
            if (f.name.rfind("border", 0) == 0) cf.border.push_back(f.name);
        }
        if (cf.border.size() < 3) continue;
        return cf;
    }
    throw BadInput("", "no disc of faces round the front of the mesh was found for a chart");
}

std::string chart_features_to_json(const std::vector<ChartFeatures>& charts) {
    nlohmann::ordered_json j;
    j["units"] = "pixels";
    j["charts"] = nlohmann::ordered_json::array();
    for (const ChartFeatures& c : charts) {
        nlohmann::ordered_json ch;
        ch["name"] = c.name;
        if (!c.features.image.empty()) ch["image"] = c.features.image;
        if (c.features.image_size) ch["image_size"] = {(*c.features.image_size)[0], (*c.features.image_size)[1]};
        ch["border"] = c.border;
        ch["features"] = nlohmann::ordered_json::array();
        for (const Feature& f : c.features.features) {
            nlohmann::ordered_json e;
            e["name"] = f.name;
            if (f.vertex >= 0) e["vertex"] = f.vertex;
            else if (f.point) e["point"] = {f.point->x(), f.point->y(), f.point->z()};
            e["image"] = {f.image.x(), f.image.y()};
            ch["features"].push_back(e);
        }
        j["charts"].push_back(ch);
    }
    return j.dump(2);
}

}  // namespace ctmap
