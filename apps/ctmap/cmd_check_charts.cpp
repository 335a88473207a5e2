// `ctmap check` of a map with several charts (issue 13): each chart is certified with its own
// image's feature UVs: one orientation per chart, every feature exact in every chart it is in,
// each chart's UV border simple.
#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "commands.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/io/chart_features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/printable.h"

namespace ctmap::cli {

int check_charts(const std::string& map_path, const std::string& features_path, bool as_json, double snap) {
    std::string ext = std::filesystem::path(map_path).extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const bool glb = ext == ".glb";
    std::vector<ChartMaterial> materials;
    const TexturedMesh tm = glb ? read_glb(map_path) : read_textured_obj(map_path, nullptr, &materials);
    if (tm.uvs.empty() || tm.uv_faces.size() != tm.mesh.faces.size())
        throw BadInput(map_path, "no texture coordinates (`vt` and `f v/vt`): there is no map to check");
    ChartFile file = read_chart_features(features_path);
    std::vector<std::array<int, 2>> sizes;
    resolve_chart_images(file, sizes);
    // A GLB splits a seam vertex into one glTF vertex per chart, at the same position: an
    // occurrence takes the copy its chart's faces use.
    std::map<std::array<double, 3>, std::vector<int>> copies;
    std::vector<std::set<int>> charts_of(tm.mesh.positions.size());
    if (glb) {
        for (std::size_t v = 0; v < tm.mesh.positions.size(); ++v) {
            const Vec3& p = tm.mesh.positions[v];
            copies[{p.x(), p.y(), p.z()}].push_back(int(v));
        }
        for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f)
            for (int v : tm.mesh.faces[f]) charts_of[v].insert(tm.chart[f]);
    }
    auto in_chart = [&](int v, int chart) {
        if (!glb || charts_of[v].count(chart)) return v;
        const Vec3& p = tm.mesh.positions[v];
        for (int w : copies[{p.x(), p.y(), p.z()}])
            if (charts_of[w].count(chart)) return w;
        return v;
    };
    std::vector<int> vertices, charts;
    std::vector<Vec2> uvs;
    std::vector<std::string> names;
    for (std::size_t c = 0; c < file.charts.size(); ++c) {
        const ChartFeatures& cf = file.charts[c];
        // The chart's faces: its material `chart_<name>` in an OBJ, primitive c in a GLB.
        int chart = int(c);
        if (!glb) {
            chart = -1;
            for (std::size_t m = 0; m < materials.size(); ++m)
                if (materials[m].name == chart_material_name(cf.name)) chart = int(m);
            if (chart < 0)
                throw BadInput(map_path, "no material " + chart_material_name(cf.name) + " for chart " + quoted_name(cf.name) + " of " +
                                             features_path + ": was this map made from these charts?");
        }
        check_features_on_mesh(cf.features, tm.mesh, map_path, snap);
        const std::vector<int> fv = feature_vertices_on_map(cf.features, tm.mesh, map_path, snap);
        for (std::size_t i = 0; i < fv.size(); ++i) {
            Vec2 uv = image_to_uv(cf.features.features[i].image, sizes[c][0], sizes[c][1]);
            if (glb) uv = Vec2(double(float(uv.x())), 1.0 - double(float(1.0 - uv.y())));  // as write_glb stores it
            vertices.push_back(in_chart(fv[i], chart));
            uvs.push_back(uv);
            charts.push_back(chart);
            names.push_back(printable(cf.name + "/" + cf.features.features[i].name));
        }
    }
    CertifyOptions opt;
    opt.feature_chart = charts;
    Certificate c;
    try {
        c = certify(tm, vertices, uvs, opt);
    } catch (const BadInput& e) {  // "feature i ..." by index: name it
        std::string problem = e.problem();
        for (std::size_t i = names.size(); i-- > 0;)
            if (problem.rfind("feature " + std::to_string(i) + ":", 0) == 0) problem = "feature " + names[i] + problem.substr(8 + std::to_string(i).size());
        throw BadInput(map_path, problem);
    }
    if (as_json) {
        std::cout << certificate_to_json(c).dump(2) << "\n";
    } else {
        std::cout << map_path << ": " << (c.valid ? "valid" : "INVALID") << " (" << c.triangles << " triangles, "
                  << file.charts.size() << (file.charts.size() == 1 ? " chart, " : " charts, ") << vertices.size() << " feature occurrences)\n"
                  << "  flipped " << c.flipped << ", degenerate " << c.degenerate << ", feature error "
                  << c.feature_max_error << (c.worst_feature >= 0 ? " (" + names[c.worst_feature] + ")" : "")
                  << ", every chart's border "
                  << (c.border_simple ? "simple" : "NOT simple (" + std::to_string(c.border_crossings) + " crossings)") << "\n";
    }
    return c.valid ? kExitOk : kExitInvalid;
}

}  // namespace ctmap::cli
