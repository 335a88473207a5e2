#include "ctmap/map_texture.h"
#include "ctmap/input_faces.h"
#include "ctmap/unit_box.h"

#include "ctmap/io/mesh_topology.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <limits>
#include <numeric>
#include <tuple>
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
/// vertices keep their indices) and returns every feature's vertex. A point within `vertex_snap`
/// of a vertex of its closest face (and within a quarter of that vertex's shortest edge there,
/// so distinct points on a dense mesh stay distinct) uses that vertex: coordinates printed with
/// 4 decimals land on the vertex they were copied from. A point within 1e-6 of the diagonal of an
/// edge splits the edge (no sliver faces). `moved` receives the largest distance a point moved.
std::vector<int> feature_vertices(TriMesh& mesh, const std::vector<MapFeature>& features, double vertex_snap,
                                  int& inserted, double& moved) {
    std::vector<int> vertex(features.size(), -1);
    inserted = 0;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
    for (const Vec3& p : mesh.positions) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
    }
    // 1e-6 of the diagonal: a point copied from a float32 file (PLY, STL) or printed with 7
    // digits lands this close to its vertex, and a vertex inserted there would make slivers.
    const double snap = 1e-6 * (hi - lo).norm();
    moved = 0;
    const int input_vertices = mesh.num_vertices();
    std::unique_ptr<WorkMesh> wm;
    for (std::size_t i = 0; i < features.size(); ++i) {
        if (features[i].vertex >= 0) {
            vertex[i] = features[i].vertex;
            continue;
        }
        if (!wm) wm = std::make_unique<WorkMesh>(mesh);
        const Vec3& p = features[i].point;
        if (features[i].vertex < -1 || !p.allFinite())
            throw BadInput("", "feature \"" + features[i].name + "\": give a vertex index (>= 0) or a finite 3D point");
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
        // A point farther from the surface than the tolerance is a caller's mistake (the CLI says so
        // before, through check_features_on_mesh; library callers learn it here).
        const double diag = (hi - lo).norm(), allowed = std::max(snap, vertex_snap);
        if (best_face < 0 || !(std::sqrt(best) <= allowed * (1 + 1e-9)))
            throw BadInput("", "feature \"" + features[i].name + "\": its point is " +
                                     (best_face < 0 ? std::string("far") : std::to_string(std::sqrt(best) / diag) + " of the mesh's diagonal") +
                                     " off the surface (at most " + std::to_string(allowed / diag) + " allowed; --snap)");
        const Tri& t = wm->faces[best_face];
        int at_vertex = -1;
        double at_distance = std::numeric_limits<double>::max();
        for (int k = 0; k < 3; ++k) {
            const Vec3& v = wm->positions[t[k]];
            const double shortest = std::min((wm->positions[t[(k + 1) % 3]] - v).norm(), (wm->positions[t[(k + 2) % 3]] - v).norm());
            const double d = (v - p).norm();
            // An input vertex within the snap distance; a vertex inserted for another point feature
            // only where the two points coincide (two nearby features stay two features).
            const double limit = t[k] < input_vertices ? std::max(snap, std::min(vertex_snap, 0.25 * shortest)) : snap;
            if (d <= limit && d < at_distance) at_vertex = t[k], at_distance = d;
        }
        if (at_vertex >= 0) {
            vertex[i] = at_vertex;
            moved = std::max(moved, at_distance);
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
        moved = std::max(moved, (wm->positions[vertex[i]] - p).norm());
        ++inserted;
    }
    if (wm) {
        mesh.positions = wm->positions;
        mesh.faces = wm->faces;
    }
    return vertex;
}

/// The mesh in the unit box with the point features inserted: what every stage after reading
/// starts from (map_texture and check_feature_layout alike).
struct Prepared {
    UnitBox box;
    TriMesh mesh;
    std::vector<int> feature_vertex;
    std::vector<std::string> names;
    std::vector<Vec2> uv;
    int point_features = 0;
    double moved = 0;  ///< the largest distance a point feature moved onto the mesh (input units)
};

/// The mesh's share of `prepare`: everything but the image points.
Prepared prepare_mesh(const TriMesh& input, const std::vector<MapFeature>& features, double snap) {
    Prepared p;
    // A caller's mesh that is no disc is a BadInput here, not a failure deep in the cut.
    require_disc(compute_topology(input), "");
    // The pipeline runs in the unit box (UnitBox); map_texture puts the input's coordinates back.
    p.box = UnitBox::of(input);
    p.mesh = input;
    for (Vec3& q : p.mesh.positions) q = p.box.in(q);
    std::vector<MapFeature> unit_features = features;
    for (MapFeature& f : unit_features)
        if (f.vertex < 0) f.point = p.box.in(f.point);
    for (const MapFeature& f : features)
        if (f.vertex >= input.num_vertices())
            throw BadInput("", "feature \"" + f.name + "\": vertex " + std::to_string(f.vertex) +
                                              " does not exist (the mesh has " + std::to_string(input.num_vertices()) +
                                              " vertices)");
    const double unit_snap = snap >= 0 ? snap / p.box.half : kDefaultSnapFraction * diagonal(p.mesh);
    p.feature_vertex = feature_vertices(p.mesh, unit_features, unit_snap, p.point_features, p.moved);
    p.moved *= p.box.half;
    const std::vector<int>& fv = p.feature_vertex;
    for (std::size_t i = 0; i < fv.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (fv[i] == fv[j])
                throw BadInput("", "features \"" + features[j].name + "\" and \"" + features[i].name +
                                                  "\" are at the same mesh vertex " + std::to_string(fv[i]));
    return p;
}

/// The image points' share of `prepare`: finite and distinct, into `p.names` and `p.uv`.
void prepare_image_points(Prepared& p, const std::vector<MapFeature>& features) {
    p.names.clear();
    p.uv.clear();
    for (const MapFeature& f : features) {
        if (!f.uv.allFinite())
            throw BadInput("", "feature \"" + f.name + "\": its UV is not finite (NaN or infinity)");
        p.names.push_back(f.name);
        p.uv.push_back(f.uv);
    }
    // Distinct image points (a caller's mistake, not the triangulation's): sorted, neighbours compared.
    std::vector<int> order(features.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return std::tie(p.uv[a].x(), p.uv[a].y()) < std::tie(p.uv[b].x(), p.uv[b].y());
    });
    for (std::size_t k = 1; k < order.size(); ++k)
        if (p.uv[order[k]] == p.uv[order[k - 1]]) {
            const int a = std::min(order[k - 1], order[k]), b = std::max(order[k - 1], order[k]);
            throw BadInput("", "features \"" + features[a].name + "\" and \"" + features[b].name +
                                              "\" have the same image point; each feature needs its own");
        }
}

Prepared prepare(const TriMesh& input, const std::vector<MapFeature>& features, double snap) {
    Prepared p = prepare_mesh(input, features, snap);
    prepare_image_points(p, features);
    return p;
}

/// Places the automatic border (domain/auto_border.h) when the given features need one and
/// appends its features to `in` (after the given ones, named auto_border_1, ...).
AutoBorder add_border_features(const TriMesh& mesh, std::vector<int>& feature_vertex, std::vector<Vec2>& uv,
                               std::vector<std::string>& names) {
    AutoBorder added = place_border_features(mesh, feature_vertex, uv, names);
    for (std::size_t j = 0; j < added.vertex.size(); ++j) {
        std::string name = "auto_border_" + std::to_string(j + 1);
        while (std::find(names.begin(), names.end(), name) != names.end()) name += "'";
        names.push_back(name);
        added.name.push_back(name);
        feature_vertex.push_back(added.vertex[j]);
        uv.push_back(added.uv[j]);
    }
    return added;
}

AutoBorder add_border_features(Prepared& in) { return add_border_features(in.mesh, in.feature_vertex, in.uv, in.names); }

}  // namespace

FeatureLayout check_feature_layout(const TriMesh& input, const std::vector<MapFeature>& features,
                                   double snap, bool auto_border) {
    Prepared in = prepare(input, features, snap);
    FeatureLayout out;
    if (auto_border) out.auto_border = add_border_features(in);
    out.triangulation = triangulate_features(in.uv, border_features(in.mesh, in.feature_vertex), in.names);
    return out;
}

struct FeatureLayoutChecker::State {
    Prepared prepared;                 // the mesh's share, image points not yet set
    std::vector<int> border_features;  // of the given features (what the triangulation needs without an added border)
};

FeatureLayoutChecker::FeatureLayoutChecker(const TriMesh& mesh, const std::vector<MapFeature>& features, double snap,
                                           bool auto_border)
    : auto_border_(auto_border) {
    auto st = std::make_shared<State>();
    st->prepared = prepare_mesh(mesh, features, snap);
    st->border_features = ctmap::border_features(st->prepared.mesh, st->prepared.feature_vertex);
    for (const MapFeature& f : features) names_.push_back(f.name), vertex_.push_back(f.vertex), point_.push_back(f.point);
    state_ = std::move(st);
}

FeatureLayout FeatureLayoutChecker::check(const std::vector<MapFeature>& features) const {
    bool same = features.size() == names_.size();
    for (std::size_t i = 0; same && i < features.size(); ++i)
        same = features[i].name == names_[i] && features[i].vertex == vertex_[i] &&
               (features[i].vertex >= 0 || features[i].point == point_[i]);
    if (!same) throw BadInput("", "FeatureLayoutChecker::check: the features differ from the checker's in more than their UVs");
    const Prepared& p = state_->prepared;
    Prepared in;  // the image points' share, with p's mesh read in place (not copied)
    in.feature_vertex = p.feature_vertex;
    prepare_image_points(in, features);
    FeatureLayout out;
    if (auto_border_) out.auto_border = add_border_features(p.mesh, in.feature_vertex, in.uv, in.names);
    out.triangulation = triangulate_features(
        in.uv, out.auto_border.vertex.empty() ? state_->border_features : border_features(p.mesh, in.feature_vertex),
        in.names);
    return out;
}

std::vector<int> place_point_features(TriMesh& mesh, const std::vector<MapFeature>& features, double snap) {
    const UnitBox box = UnitBox::of(mesh);
    TriMesh unit = mesh;
    for (Vec3& q : unit.positions) q = box.in(q);
    std::vector<MapFeature> unit_features = features;
    for (MapFeature& f : unit_features)
        if (f.vertex < 0) f.point = box.in(f.point);
    const double unit_snap = snap >= 0 ? snap / box.half : kDefaultSnapFraction * diagonal(unit);
    int inserted = 0;
    double moved = 0;
    const std::vector<int> vertex = feature_vertices(unit, unit_features, unit_snap, inserted, moved);
    // The input's vertices keep their exact coordinates; only the inserted ones come back from the box.
    const int n = mesh.num_vertices();
    mesh.faces = unit.faces;
    for (int i = n; i < unit.num_vertices(); ++i) mesh.positions.push_back(box.out(unit.positions[i]));
    return vertex;
}

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

MapResult map_texture(const TriMesh& input, const std::vector<MapFeature>& features, const MapOptions& options) {
    const auto start = Clock::now();
    auto stage = [&](const char* name) {
        if (options.progress) options.progress(name, 0, 0);
    };
    MapResult r;
    Prepared in = prepare(input, features, options.snap);
    const std::size_t given = in.feature_vertex.size();
    if (options.auto_border) r.auto_border = add_border_features(in);
    TriMesh& mesh = in.mesh;
    const std::vector<int>& fv = in.feature_vertex;
    const UnitBox& box = in.box;
    r.point_features = in.point_features;
    r.point_features_moved = in.moved;
    r.feature_uv = in.uv;

    stage("triangulate");
    auto t0 = Clock::now();
    r.triangulation = triangulate_features(r.feature_uv, border_features(mesh, fv), in.names);
    r.timings_ms.triangulate = ms_since(t0);

    stage("paths");
    t0 = Clock::now();
    CutOptions copt = options.cut;
    if (options.progress && !copt.progress)
        copt.progress = [&](const std::string& stage, int done, int total) { options.progress(stage, done, total); };
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
        RelaxOptions ropt = options.relax;
        const bool isometric = options.refine_mode == RefineMode::isometric;
        if (isometric && options.isometric.border == BorderMode::fixed) ropt.move_border = false;
        // The border stays in the image (or in the embedding's box, if that reaches outside).
        ropt.keep_in_box = !isometric || options.isometric.keep_in_box;
        ropt.box_lo = options.isometric.box_lo, ropt.box_hi = options.isometric.box_hi;  // the optimiser's image
        for (const Vec2& p : r.uv) ropt.box_lo = ropt.box_lo.cwiseMin(p), ropt.box_hi = ropt.box_hi.cwiseMax(p);
        r.relax_stats = relax(r.cut.mesh, r.uv, r.cut.feature_vertex, ropt);
        r.timings_ms.refine = ms_since(t0);
        if (isometric) {
            r.after_relax = measure_distortion(r.textured());
            stage("optimise");
            t0 = Clock::now();
            IsometricOptions iopt = options.isometric;
            if (options.progress) {
                const auto user = iopt.on_iteration;
                iopt.on_iteration = [&, user](int it, const std::vector<Vec2>& uv, double e) {
                    if (user) user(it, uv, e);
                    options.progress("optimise", it, iopt.max_iterations);
                };
            }
            // The added border features only start a free border: the optimiser moves them.
            std::vector<int> fixed = r.cut.feature_vertex;
            if (iopt.border == BorderMode::free) fixed.resize(given), r.auto_border_fixed = false;
            r.isometric_stats = optimise_isometric(r.cut.mesh, r.uv, fixed, iopt);
            r.timings_ms.optimise = ms_since(t0);
        }
    }

    r.cut.feature_vertex.resize(given);  // the given features (the added ones are in r.auto_border)
    r.feature_uv.resize(given);
    stage("certify");
    t0 = Clock::now();
    r.certificate = certify(r.textured(), r.cut.feature_vertex, r.feature_uv);
    r.timings_ms.certify = ms_since(t0);
    if (!options.refine) r.before_refine = r.certificate.distortion;
    if (!options.refine || options.refine_mode != RefineMode::isometric) r.after_relax = r.certificate.distortion;
    // The faces of each patch together (in patch order, each patch's in the cut's order), so a
    // written OBJ has one group per patch rather than a switch at every other face.
    std::vector<int> order(r.cut.mesh.faces.size());
    for (std::size_t f = 0; f < order.size(); ++f) order[f] = int(f);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return r.cut.face_patch[a] < r.cut.face_patch[b]; });
    std::vector<Tri> faces(order.size());
    std::vector<int> patch(order.size());
    for (std::size_t f = 0; f < order.size(); ++f) faces[f] = r.cut.mesh.faces[order[f]], patch[f] = r.cut.face_patch[order[f]];
    r.cut.mesh.faces = std::move(faces);
    r.cut.face_patch = std::move(patch);
    // Back to the input's coordinates: its own vertices exactly, the inserted ones through the box.
    std::vector<Vec3>& out = r.cut.mesh.positions;
    for (std::size_t v = 0; v < out.size(); ++v)
        out[v] = v < input.positions.size() ? input.positions[v] : box.out(out[v]);
    // The optimiser's scale, for the mesh as returned: a run continued on r.cut.mesh with it
    // minimises the same energy (IsometricOptions::scale).
    r.isometric_stats.scale /= box.half;
    r.input_face = input_faces_of(input, r.cut.mesh);
    r.timings_ms.total = ms_since(start);
    if (!r.certificate.valid)
        throw InternalError("the map failed its certificate (" + std::to_string(r.certificate.flipped) + " flipped, " +
                            std::to_string(r.certificate.degenerate) + " degenerate, feature error " +
                            std::to_string(r.certificate.feature_max_error) + ", border " +
                            (r.certificate.border_simple ? "simple" : "not simple") + "); nothing was written");
    return r;
}

}  // namespace ctmap

namespace ctmap {

MapArrays map_texture(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<MapFeature>& features,
                      const MapOptions& options) {
    if (V.cols() != 3) throw BadInput("V", "must have 3 columns (x, y, z), has " + std::to_string(V.cols()));
    if (F.cols() != 3) throw BadInput("F", "must have 3 columns (a triangle's vertices), has " + std::to_string(F.cols()));
    TriMesh mesh;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
        if (!V.row(i).allFinite()) throw BadInput("V", "vertex " + std::to_string(i) + " has a non-finite coordinate");
        mesh.positions.emplace_back(V(i, 0), V(i, 1), V(i, 2));
    }
    for (Eigen::Index i = 0; i < F.rows(); ++i) {
        for (int k = 0; k < 3; ++k)
            if (F(i, k) < 0 || F(i, k) >= V.rows())
                throw BadInput("F", "face " + std::to_string(i) + " has vertex index " + std::to_string(F(i, k)) +
                                        " out of range (there are " + std::to_string(V.rows()) + " vertices)");
        mesh.faces.push_back({F(i, 0), F(i, 1), F(i, 2)});
    }
    MapArrays out;
    out.result = map_texture(mesh, features, options);
    const MapResult& r = out.result;
    const TexturedMesh tm = r.textured();
    out.V.resize(r.cut.mesh.num_vertices(), 3);
    for (int i = 0; i < r.cut.mesh.num_vertices(); ++i) out.V.row(i) = r.cut.mesh.positions[i].transpose();
    out.F.resize(r.cut.mesh.num_faces(), 3);
    out.UV.resize(3 * Eigen::Index(r.cut.mesh.num_faces()), 2);
    out.chart.resize(r.cut.mesh.num_faces());
    for (int f = 0; f < r.cut.mesh.num_faces(); ++f) {
        for (int k = 0; k < 3; ++k) {
            out.F(f, k) = r.cut.mesh.faces[f][k];
            out.UV.row(3 * Eigen::Index(f) + k) = tm.uvs[tm.uv_faces[f][k]].transpose();
        }
        out.chart(f) = tm.chart[f];
    }
    out.feature_vertex.resize(Eigen::Index(r.cut.feature_vertex.size()));
    for (std::size_t i = 0; i < r.cut.feature_vertex.size(); ++i) out.feature_vertex(Eigen::Index(i)) = r.cut.feature_vertex[i];
    return out;
}

}  // namespace ctmap
