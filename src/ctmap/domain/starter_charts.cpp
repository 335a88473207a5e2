#include "ctmap/domain/starter_charts.h"

#include <nlohmann/json.hpp>

#include "ctmap/cut/chart_regions.h"
#include "ctmap/domain/bisection_seam.h"
#include "ctmap/errors.h"

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
