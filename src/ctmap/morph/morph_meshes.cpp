#include "ctmap/morph/morph_meshes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "ctmap/border_loop.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/printable.h"
#include "ctmap/morph/surface_distance.h"

#include <memory>

namespace ctmap {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// A morph needs two discs: charts are built into `map`, not yet into the morph (issue 13).
void require_morph_disc(const TriMesh& mesh, const std::string& file) {
    const MeshTopology topo = compute_topology(mesh);
    if (topo.is_closed)
        throw TopologyError(file, "the mesh is closed (no border): ctmap morph maps discs; a morph with charts and "
                                  "seams is not available yet: cut it open first");
    require_disc(topo, file, NotDiscAdvice::cut_open);
}

/// One side's pair ends as features on `mesh` (point ends inserted as vertices).
std::vector<int> place_ends(TriMesh& mesh, const PairSet& set, bool source, double snap, const std::string& file) {
    const char* side = source ? "source" : "target";
    std::vector<MapFeature> ends;
    for (const FeaturePair& p : set.pairs) {
        const PairEnd& e = source ? p.source : p.target;
        MapFeature f;
        f.name = p.name;
        f.vertex = e.vertex;
        if (e.vertex >= mesh.num_vertices())
            throw BadInput(set.path, "pair " + quoted_name(p.name) + ": " + side + " vertex " +
                                         std::to_string(e.vertex) + " does not exist (" + file + " has " + std::to_string(mesh.num_vertices()) +
                                         " vertices)");
        if (e.vertex < 0 && !e.point)
            throw BadInput(set.path,
                           "pair " + quoted_name(p.name) + ": the " + side + " end has neither a vertex nor a point");
        if (e.vertex < 0) f.point = *e.point;
        ends.push_back(f);
    }
    Eigen::AlignedBox3d box;
    for (const Vec3& q : mesh.positions) box.extend(q);
    const double tolerance = snap >= 0 ? snap : kDefaultSnapFraction * box.diagonal().norm();
    std::unique_ptr<SurfaceDistance> surface;
    for (std::size_t i = 0; i < ends.size(); ++i) {
        if (ends[i].vertex >= 0) continue;
        if (!surface) surface = std::make_unique<SurfaceDistance>(mesh);
        const double d = surface->distance(ends[i].point);
        if (!(d <= tolerance))
            throw BadInput(set.path, "pair " + quoted_name(ends[i].name) + ": the " + side + " point is " +
                                         std::to_string(d) + " off the surface of " + file + " (more than " + std::to_string(tolerance) +
                                         "); give a point on the surface or a vertex");
    }
    const std::vector<int> vertex = place_point_features(mesh, ends, snap);
    for (std::size_t i = 0; i < vertex.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
            if (vertex[i] == vertex[j])
                throw BadInput(set.path, "pairs " + quoted_name(ends[j].name) + " and " + quoted_name(ends[i].name) +
                                             " are at the same " + side + " vertex " + std::to_string(vertex[i]));
    return vertex;
}

/// The pairs on the border, in the order of the border loop, with their arc-length fractions.
struct BorderPairs {
    std::vector<int> pair;    ///< pair indices in border order, starting anywhere
    std::vector<double> at;   ///< arc length from the loop's start, as a fraction of the border
};

BorderPairs border_pairs(const TriMesh& mesh, const std::vector<int>& vertex) {
    const std::vector<int> loop = border_loop(mesh);
    std::vector<int> pair_at(mesh.positions.size(), -1);
    for (std::size_t i = 0; i < vertex.size(); ++i) pair_at[vertex[i]] = int(i);
    BorderPairs out;
    double length = 0;
    for (std::size_t k = 0; k < loop.size(); ++k) {
        if (pair_at[loop[k]] >= 0) {
            out.pair.push_back(pair_at[loop[k]]);
            out.at.push_back(length);
        }
        length += (mesh.positions[loop[(k + 1) % loop.size()]] - mesh.positions[loop[k]]).norm();
    }
    for (double& a : out.at) a /= length;
    return out;
}

std::string names_in_order(const PairSet& set, const std::vector<int>& order) {
    std::string s;
    for (int i : order) s += (s.empty() ? "" : ", ") + quoted_name(set.pairs[i].name);
    return s;
}

}  // namespace

MorphResult morph_meshes(const TriMesh& source_in, const TriMesh& target_in, const PairSet& pairs,
                         const MorphOptions& options, const std::string& source_file, const std::string& target_file) {
    const auto start = Clock::now();
    require_morph_disc(source_in, source_file);
    require_morph_disc(target_in, target_file);
    if (pairs.pairs.empty()) throw BadInput(pairs.path, "no pairs: a morph needs at least 3 border pairs");
    TriMesh source = source_in, target = target_in;
    const std::vector<int> sv = place_ends(source, pairs, true, options.snap, source_file);
    const std::vector<int> tv = place_ends(target, pairs, false, options.snap, target_file);

    // Border pairs: on both borders, at least 3, in the same cyclic order.
    const BorderPairs sb = border_pairs(source, sv), tb = border_pairs(target, tv);
    std::vector<bool> on_source(pairs.pairs.size()), on_target(pairs.pairs.size());
    for (int i : sb.pair) on_source[i] = true;
    for (int i : tb.pair) on_target[i] = true;
    std::string one_sided;
    for (std::size_t i = 0; i < pairs.pairs.size(); ++i)
        if (on_source[i] != on_target[i])
            one_sided += "\n  - pair " + quoted_name(pairs.pairs[i].name) + " lies on the " +
                         (on_source[i] ? "source" : "target") + "'s border but not on the " + (on_source[i] ? "target" : "source") + "'s";
    if (!one_sided.empty())
        throw BadInput(pairs.path, "a pair on one border must lie on both (border pairs bound the morph):" + one_sided);
    if (tb.pair.size() < 3)
        throw BadInput(pairs.path, "only " + std::to_string(tb.pair.size()) + " pair(s) lie on the meshes' borders (" +
                                       names_in_order(pairs, tb.pair) +
                                       "): a morph needs at least 3 border pairs, in the same order along both borders");
    // Both orders turned to start at the first border pair of the file.
    BorderPairs t_border = tb;
    std::vector<int> s_order = sb.pair;
    std::vector<double> s_at = sb.at;
    const int lead = *std::min_element(tb.pair.begin(), tb.pair.end());
    const auto tf0 = std::find(t_border.pair.begin(), t_border.pair.end(), lead) - t_border.pair.begin();
    std::rotate(t_border.pair.begin(), t_border.pair.begin() + tf0, t_border.pair.end());
    std::rotate(t_border.at.begin(), t_border.at.begin() + tf0, t_border.at.end());
    const auto first = std::find(s_order.begin(), s_order.end(), lead) - s_order.begin();
    std::rotate(s_order.begin(), s_order.begin() + first, s_order.end());
    std::rotate(s_at.begin(), s_at.begin() + first, s_at.end());
    if (s_order != t_border.pair)
        throw BadInput(pairs.path, "the border pairs come in a different cyclic order along the source's border (" +
                                       names_in_order(pairs, s_order) + ") than along the target's (" +
                                       names_in_order(pairs, t_border.pair) +
                                       "); reorder them, or flip one mesh's faces if it is oriented the other way");

    // The polygon: border pairs on a circle, at the mean of their two arc-length fractions.
    MorphResult out;
    const double pi = std::numbers::pi;
    std::vector<Vec2> corner(pairs.pairs.size(), Vec2(0, 0));
    for (std::size_t k = 0; k < t_border.pair.size(); ++k) {
        double fs = s_at[k] - s_at[0], ft = t_border.at[k] - t_border.at[0];
        if (fs < 0) fs += 1;
        if (ft < 0) ft += 1;
        const double a = 2 * pi * 0.5 * (fs + ft);
        corner[t_border.pair[k]] = Vec2(0.5 + 0.45 * std::cos(a), 0.5 + 0.45 * std::sin(a));
        out.border_pairs.push_back(pairs.pairs[t_border.pair[k]].name);
    }

    MapOptions mo = options.map;
    mo.auto_border = false;
    mo.isometric.border = BorderMode::fixed;

    // The target onto the polygon: its border pairs are its only features.
    if (options.progress) options.progress("target map");
    auto t0 = Clock::now();
    std::vector<MapFeature> tf;
    for (int i : t_border.pair) {
        MapFeature f;
        f.name = pairs.pairs[i].name;
        f.vertex = tv[i];
        f.uv = corner[i];
        tf.push_back(f);
    }
    out.target_map = naming_file(pairs.path, [&] { return map_texture(target, tf, mo); });
    out.timings_ms.target_map = ms_since(t0);

    // The source onto the target's map: every pair at its target's point.
    if (options.progress) options.progress("source map");
    t0 = Clock::now();
    std::vector<MapFeature> sf;
    for (std::size_t i = 0; i < pairs.pairs.size(); ++i) {
        MapFeature f;
        f.name = pairs.pairs[i].name;
        f.vertex = sv[i];
        f.uv = out.target_map.uv[tv[i]];
        sf.push_back(f);
    }
    out.source_map = naming_file(pairs.path, [&] { return map_texture(source, sf, mo); });
    out.timings_ms.source_map = ms_since(t0);

    if (options.progress) options.progress("common mesh");
    t0 = Clock::now();
    out.common = common_mesh({&out.source_map.cut.mesh, &out.source_map.uv},
                             {&out.target_map.cut.mesh, &out.target_map.uv}, {options.resample});
    out.pair_vertex = sv;
    out.target_pair_vertex = tv;  // the source's vertices keep their indices through the cut and the common mesh
    if (options.align) {
        Eigen::Matrix3Xd from(3, sv.size()), to(3, tv.size());
        for (std::size_t i = 0; i < sv.size(); ++i) {
            from.col(Eigen::Index(i)) = source.positions[sv[i]];
            to.col(Eigen::Index(i)) = target.positions[tv[i]];
        }
        out.alignment = Eigen::umeyama(from, to, true);
        const Eigen::Affine3d a(out.alignment);
        if (a.matrix().allFinite())
            for (Vec3& p : out.common.mesh.positions) p = a * p;
        else
            out.alignment.setIdentity();
    }
    out.timings_ms.common_mesh = ms_since(t0);
    out.timings_ms.total = ms_since(start);
    return out;
}

std::vector<Vec3> morph_frame(const CommonMesh& common, double w) {
    std::vector<Vec3> p(common.mesh.positions.size());
    for (std::size_t i = 0; i < p.size(); ++i)
        p[i] = w == 0 ? common.mesh.positions[i] : w == 1 ? common.target_position[i]
                                                          : Vec3((1 - w) * common.mesh.positions[i] + w * common.target_position[i]);
    return p;
}

}  // namespace ctmap
