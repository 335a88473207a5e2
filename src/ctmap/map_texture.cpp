#include "ctmap/map_texture.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>

#include "ctmap/cut/insert_path.h"
#include "ctmap/cut/work_mesh.h"
#include "ctmap/errors.h"

namespace ctmap {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Barycentric coordinates of the point of triangle (a, b, c) closest to p (Ericson, Real-Time
/// Collision Detection §5.1.5).
Vec3 closest_bary(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0 && d2 <= 0) return Vec3(1, 0, 0);
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0 && d4 <= d3) return Vec3(0, 1, 0);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return Vec3(1 - v, v, 0);
    }
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0 && d5 <= d6) return Vec3(0, 0, 1);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return Vec3(1 - w, 0, w);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return Vec3(0, 1 - w, w);
    }
    const double denom = 1 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    return Vec3(1 - v - w, v, w);
}

/// Inserts the point features of `features` into `mesh` as vertices (appended, so the input's
/// vertices keep their indices) and returns every feature's vertex. A point within 1e-9 of the
/// bounding-box diagonal of a vertex uses that vertex; one as close to an edge splits the edge
/// (no sliver faces).
std::vector<int> feature_vertices(TriMesh& mesh, const std::vector<MapFeature>& features, int& inserted) {
    std::vector<int> vertex(features.size(), -1);
    inserted = 0;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (const Vec3& p : mesh.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    const double snap = 1e-9 * (hi - lo).norm();
    std::unique_ptr<WorkMesh> wm;
    for (std::size_t i = 0; i < features.size(); ++i) {
        if (features[i].vertex >= 0) {
            vertex[i] = features[i].vertex;
            continue;
        }
        if (!wm) wm = std::make_unique<WorkMesh>(mesh);
        const Vec3& p = features[i].point;
        int best_face = -1;
        Vec3 best_bary;
        double best = std::numeric_limits<double>::max();
        for (int f = 0; f < int(wm->faces.size()); ++f) {
            const Tri& t = wm->faces[f];
            const Vec3 l = closest_bary(p, wm->positions[t[0]], wm->positions[t[1]], wm->positions[t[2]]);
            const Vec3 q = l[0] * wm->positions[t[0]] + l[1] * wm->positions[t[1]] + l[2] * wm->positions[t[2]];
            const double d = (q - p).squaredNorm();
            if (d < best) best = d, best_face = f, best_bary = l;
        }
        const Tri& t = wm->faces[best_face];
        int at_vertex = -1;
        for (int k = 0; k < 3; ++k)
            if ((wm->positions[t[k]] - p).norm() <= snap) at_vertex = t[k];
        if (at_vertex >= 0) {
            vertex[i] = at_vertex;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            const Vec3 a = wm->positions[t[(k + 1) % 3]], b = wm->positions[t[(k + 2) % 3]];
            const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
            if ((a + s * (b - a) - p).norm() <= snap) {
                best_bary = Vec3::Zero();
                best_bary[(k + 1) % 3] = 1 - s;
                best_bary[(k + 2) % 3] = s;
            }
        }
        vertex[i] = insert_point(*wm, best_face, best_bary);
        ++inserted;
    }
    if (wm) {
        mesh.positions = wm->positions;
        mesh.faces = wm->faces;
    }
    return vertex;
}

}  // namespace

std::vector<MapFeature> map_features(const FeatureSet& fs, int width, int height) {
    std::vector<MapFeature> out;
    out.reserve(fs.features.size());
    for (const Feature& f : fs.features) {
        MapFeature m;
        m.name = f.name;
        m.vertex = f.vertex;
        if (f.point) m.point = *f.point;
        m.uv = image_to_uv(f.image, width, height);
        out.push_back(m);
    }
    return out;
}

MapResult map_texture(const TriMesh& input, const std::vector<MapFeature>& features, const MapOptions& options,
                      const std::string& features_file) {
    const auto start = Clock::now();
    auto stage = [&](const char* name) {
        if (options.progress) options.progress(name, 0, 0);
    };
    MapResult r;
    TriMesh mesh = input;
    for (const MapFeature& f : features)
        if (f.vertex >= input.num_vertices())
            throw BadInput(features_file, "feature \"" + f.name + "\": vertex " + std::to_string(f.vertex) +
                                              " does not exist (the mesh has " + std::to_string(input.num_vertices()) +
                                              " vertices)");
    const std::vector<int> fv = feature_vertices(mesh, features, r.point_features);
    for (std::size_t i = 0; i < fv.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (fv[i] == fv[j])
                throw BadInput(features_file, "features \"" + features[j].name + "\" and \"" + features[i].name +
                                                  "\" are at the same mesh vertex " + std::to_string(fv[i]));
    std::vector<std::string> names;
    for (const MapFeature& f : features) {
        names.push_back(f.name);
        r.feature_uv.push_back(f.uv);
    }

    stage("triangulate");
    auto t0 = Clock::now();
    TriangulateOptions topt;
    topt.features_file = features_file;
    r.triangulation = triangulate_features(r.feature_uv, border_features(mesh, fv), names, topt);
    r.timings_ms.triangulate = ms_since(t0);

    stage("paths");
    t0 = Clock::now();
    CutOptions copt = options.cut;
    if (options.progress && !copt.progress)
        copt.progress = [&](int done, int total) { options.progress("paths", done, total); };
    r.cut = cut_mesh(mesh, fv, r.triangulation, copt, &r.cut_stats);
    r.timings_ms.paths = ms_since(t0);

    stage("embed");
    t0 = Clock::now();
    r.flat_edges = split_flat_edges(r.cut, mesh);
    r.uv = embed_patches(r.cut, r.feature_uv, options.embed);
    r.timings_ms.embed = ms_since(t0);

    if (options.refine) {
        stage("refine");
        t0 = Clock::now();
        r.before_refine = measure_distortion(r.textured());
        r.relax_stats = relax(r.cut.mesh, r.uv, r.cut.feature_vertex, options.relax);
        r.timings_ms.refine = ms_since(t0);
    }

    stage("certify");
    t0 = Clock::now();
    r.certificate = certify(r.textured(), r.cut.feature_vertex, r.feature_uv);
    r.timings_ms.certify = ms_since(t0);
    if (!options.refine) r.before_refine = r.certificate.distortion;
    r.timings_ms.total = ms_since(start);
    if (!r.certificate.valid)
        throw InternalError("the map failed its certificate (" + std::to_string(r.certificate.flipped) + " flipped, " +
                            std::to_string(r.certificate.degenerate) + " degenerate, feature error " +
                            std::to_string(r.certificate.feature_max_error) + ", border " +
                            (r.certificate.border_simple ? "simple" : "not simple") + "); nothing was written");
    return r;
}

}  // namespace ctmap
