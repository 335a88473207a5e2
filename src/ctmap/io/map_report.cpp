#include "ctmap/io/map_report.h"

#include <cmath>

namespace ctmap {
namespace {

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json distortion_json(const Distortion& d) {
    return {{"symmetric_dirichlet", number_or_null(d.symmetric_dirichlet)},
            {"conformal_mean", number_or_null(d.conformal_mean)},
            {"conformal_max", number_or_null(d.conformal_max)},
            {"area_distortion_mean", number_or_null(d.area_mean)},
            {"area_distortion_max", number_or_null(d.area_max)},
            {"l2_stretch", number_or_null(d.l2_stretch)}};
}


nlohmann::json map_report(const MapResult& r, const MapReportInputs& in) {
    nlohmann::json j;
    j["inputs"] = {{"mesh", in.mesh},
                   {"features", in.features},
                   {"image", in.image.empty() ? nlohmann::json(nullptr) : nlohmann::json(in.image)},
                   {"image_size", {in.image_width, in.image_height}}};
    j["counts"] = {{"features", r.feature_uv.size()},
                   {"point_features", r.point_features},
                   {"triangles", r.triangulation.triangles.size()},
                   {"paths", r.cut_stats.paths},
                   {"input_vertices", in.input_vertices},
                   {"input_faces", in.input_faces},
                   {"vertices", r.cut.mesh.num_vertices()},
                   {"faces", r.cut.mesh.num_faces()},
                   {"inserted_vertices", r.cut.mesh.num_vertices() - in.input_vertices},
                   {"steiner_vertices", r.cut_stats.steiner_vertices},
                   {"flat_edges_split", r.flat_edges.edges_split},
                   {"fallback_fired", r.cut_stats.fallback_fired}};
    // Why the mesh grew: each vertex the cut added lies where a path crosses an input edge, or
    // inside an input face (a path's bend that straightening kept, or a Steiner vertex).
    j["growth"] = {{"faces_added", r.cut.mesh.num_faces() - in.input_faces},
                   {"path_crossings_of_input_edges", r.cut_stats.vertices_on_input_edges},
                   {"vertices_inside_input_faces", r.cut_stats.vertices_inside_faces},
                   {"path_vertices_straightened_away", r.cut_stats.straightened_vertices},
                   {"path_length", r.cut_stats.path_length},
                   // Paths searched along the guide map (cut/guide_map.h); inserted shortest
                   // first (cut/insertion_order.h); the faces the paper's cut had reached when
                   // it was given up for those (0: it was not); the faces the shortest-first cut
                   // on the surface had reached when it was given up for the guided one.
                   {"guided_paths", r.cut_stats.guided},
                   {"shortest_paths_first", r.cut_stats.shortest_path_first},
                   {"surface_cut_given_up_at_faces", r.cut_stats.guide_restart_faces},
                   {"shortest_first_cut_given_up_at_faces", r.cut_stats.shortest_path_restart_faces},
                   // Times the input was subdivided 1-to-4 for the guided cut (its midpoints
                   // are among the vertices on input edges and inside faces above).
                   {"guide_subdivisions", r.cut_stats.guide_subdivisions}};
    nlohmann::json added = nlohmann::json::array();
    const AutoBorder& ab = r.auto_border;
    for (std::size_t i = 0; i < ab.vertex.size(); ++i) {
        const Vec2 px(ab.uv[i].x() * in.image_width, (1 - ab.uv[i].y()) * in.image_height);  // image_to_uv inverted
        added.push_back({{"name", ab.name[i]}, {"vertex", ab.vertex[i]}, {"image", {px.x(), px.y()}}});
    }
    j["auto_border"] = {{"reason", ab.reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(ab.reason)},
                        {"added", added},
                        {"kept_fixed", ab.vertex.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.auto_border_fixed)}};
    const MapTimings& t = r.timings_ms;
    j["timings_ms"] = {{"read", t.read},   {"triangulate", t.triangulate}, {"paths", t.paths}, {"embed", t.embed},
                       {"refine", t.refine}, {"optimise", t.optimise},     {"certify", t.certify},
                       {"total", t.total}};
    j["certificate"] = certificate_to_json(r.certificate);
    j["distortion_before_refine"] = distortion_json(r.before_refine);
    const RelaxStats& s = r.relax_stats;
    j["relax"] = {{"sweeps", s.iterations},
                  {"moves", s.moves},
                  {"moves_shortened", s.moves_shortened},
                  {"moves_rejected", s.moves_rejected},
                  {"free_vertices", s.free_vertices},
                  {"converged", s.converged}};
    j["distortion_after_relax"] = distortion_json(r.after_relax);
    const IsometricStats& o = r.isometric_stats;
    if (!o.energy.empty()) {
        nlohmann::json energy = nlohmann::json::array();
        for (double e : o.energy) energy.push_back(number_or_null(e));
        j["optimiser"] = {{"iterations", o.iterations},
                          {"energy", energy},
                          {"converged", o.converged},
                          {"stop", o.stop},
                          {"factorisations", o.factorisations},
                          {"halvings", o.halvings},
                          {"exact_rejections", o.exact_rejections},
                          {"border_rejections", o.border_rejections},
                          {"border_holds", o.border_holds},
                          {"free_vertices", o.free_vertices},
                          {"sliding_vertices", o.sliding_vertices}};
    } else {
        j["optimiser"] = nullptr;
    }
    return j;
}

}  // namespace ctmap
