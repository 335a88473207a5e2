#include "ctmap/certify/certificate.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <tuple>
#include <unordered_map>

#include "ctmap/errors.h"
#include "ctmap/face_jacobian.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

K::Point_2 pt(const Vec2& p) { return K::Point_2(p.x(), p.y()); }

/// c lies on the closed segment [a, b], given that a, b, c are collinear. Coordinate comparisons
/// of doubles are exact, so this stays exact.
bool between(const Vec2& a, const Vec2& b, const Vec2& c) {
    return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) && std::min(a.y(), b.y()) <= c.y() &&
           c.y() <= std::max(a.y(), b.y());
}

int sign_of(double x) { return (x > 0) - (x < 0); }

std::uint64_t bits(double d) {
    if (d == 0) d = 0;  // -0.0 and 0.0 are the same point
    std::uint64_t u;
    std::memcpy(&u, &d, sizeof u);
    return u;
}

void check_shapes(const TexturedMesh& tm) {
    const std::size_t nf = tm.mesh.faces.size();
    if (tm.uv_faces.size() != nf)
        throw BadInput("", "the map has " + std::to_string(tm.uv_faces.size()) + " UV faces for " +
                               std::to_string(nf) + " faces (every face needs texture coordinates)");
    if (!tm.chart.empty() && tm.chart.size() != nf)
        throw BadInput("", "the map has " + std::to_string(tm.chart.size()) + " chart ids for " + std::to_string(nf) +
                               " faces");
    const int nuv = int(tm.uvs.size()), nv = tm.mesh.num_vertices();
    for (std::size_t f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            if (tm.uv_faces[f][k] < 0 || tm.uv_faces[f][k] >= nuv)
                throw BadInput("", "face " + std::to_string(f) + " uses texture coordinate " +
                                       std::to_string(tm.uv_faces[f][k]) + ", but there are " + std::to_string(nuv));
            if (tm.mesh.faces[f][k] < 0 || tm.mesh.faces[f][k] >= nv)
                throw BadInput("", "face " + std::to_string(f) + " uses vertex " + std::to_string(tm.mesh.faces[f][k]) +
                                       ", but there are " + std::to_string(nv));
        }
}

}  // namespace

int orientation_2d(const Vec2& a, const Vec2& b, const Vec2& c) {
    // Shewchuk's first filter (orient2d, error bound (3 + 16 eps) eps): when the rounded
    // determinant is farther from zero than its worst rounding error, its sign is exact. The
    // relaxation asks this for every trial move, and most answers are far from zero. Near zero,
    // or where the products could underflow, CGAL's exact predicate decides.
    const double left = (a.x() - c.x()) * (b.y() - c.y());
    const double right = (a.y() - c.y()) * (b.x() - c.x());
    const double det = left - right;
    const double magnitude = std::abs(left) + std::abs(right);
    if (magnitude > 1e-280 && magnitude < 1e280) {
        const double bound = 3.3306690738754716e-16 * magnitude;
        if (det > bound) return 1;
        if (-det > bound) return -1;
    }
    return int(CGAL::orientation(pt(a), pt(b), pt(c)));
}

bool segments_intersect_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
    const int o1 = orientation_2d(a, b, c), o2 = orientation_2d(a, b, d);
    const int o3 = orientation_2d(c, d, a), o4 = orientation_2d(c, d, b);
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    if (o1 == 0 && between(a, b, c)) return true;
    if (o2 == 0 && between(a, b, d)) return true;
    if (o3 == 0 && between(c, d, a)) return true;
    if (o4 == 0 && between(c, d, b)) return true;
    return false;
}

Distortion measure_distortion(const TexturedMesh& tm) {
    check_shapes(tm);
    // Every measure is scale-invariant: measure in the unit box, so that a mesh saved in units of
    // 1e300 (or 1e-300) neither overflows nor underflows the areas.
    TriMesh m = tm.mesh;
    if (!m.positions.empty()) {
        Vec3 lo = m.positions[0], hi = lo;
        for (const Vec3& p : m.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        const Vec3 center = 0.5 * lo + 0.5 * hi;
        const double half = (0.5 * hi - 0.5 * lo).maxCoeff();
        if (half > 0 && std::isfinite(half))
            for (Vec3& p : m.positions) p = (p - center) / half;
    }
    Distortion d;
    double area3 = 0, area2 = 0;
    for (int f = 0; f < m.num_faces(); ++f) {
        const Tri& t = m.faces[f];
        const Tri& u = tm.uv_faces[f];
        area3 += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
        const Vec2 q1 = tm.uvs[u[1]] - tm.uvs[u[0]], q2 = tm.uvs[u[2]] - tm.uvs[u[0]];
        area2 += 0.5 * std::abs(q1.x() * q2.y() - q1.y() * q2.x());
    }
    const double inf = std::numeric_limits<double>::infinity();
    if (!(area3 > 0) || !(area2 > 0)) {
        d.symmetric_dirichlet = d.conformal_mean = d.conformal_max = d.area_mean = d.area_max = d.l2_stretch = inf;
        return d;
    }
    // Scale UVs to the 3D area, so that every measure is 1 (4 for the Dirichlet energy) for an
    // isometry and the numbers of different maps of one mesh compare.
    const double scale = std::sqrt(area3 / area2);
    double w_sum = 0, sd = 0, conf = 0, area = 0, l2 = 0;
    for (int f = 0; f < m.num_faces(); ++f) {
        const Tri& t = m.faces[f];
        const Tri& u = tm.uv_faces[f];
        const FaceFrame F = face_frame(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
        const double A = F.area;
        if (!(A > 0)) continue;
        const Mat2 J = face_jacobian(F, scale * tm.uvs[u[0]], scale * tm.uvs[u[1]], scale * tm.uvs[u[2]]);
        double s1, s2;
        singular_values(J, s1, s2);
        double f_sd, f_conf, f_area, f_l2;
        if (s2 > 0) {
            f_sd = s1 * s1 + s2 * s2 + 1 / (s1 * s1) + 1 / (s2 * s2);
            f_conf = s1 / s2;
            const double j = s1 * s2;
            f_area = std::max(j, 1 / j);
            f_l2 = 0.5 * (1 / (s1 * s1) + 1 / (s2 * s2));
        } else {
            f_sd = f_conf = f_area = f_l2 = inf;
        }
        w_sum += A;
        sd += A * f_sd;
        conf += A * f_conf;
        area += A * f_area;
        l2 += A * f_l2;
        d.conformal_max = std::max(d.conformal_max, f_conf);
        d.area_max = std::max(d.area_max, f_area);
        ++d.faces_measured;
    }
    if (w_sum > 0) {
        d.symmetric_dirichlet = sd / w_sum;
        d.conformal_mean = conf / w_sum;
        d.area_mean = area / w_sum;
        d.l2_stretch = std::sqrt(l2 / w_sum);
    }
    return d;
}

int count_border_crossings(const std::vector<Vec2>& pos, const std::vector<std::array<int, 2>>& border,
                           std::vector<std::array<int, 2>>* pairs) {
    int crossings = 0;
    auto cross = [&](std::size_t e, std::size_t g) {
        ++crossings;
        if (pairs) pairs->push_back({int(e), int(g)});
    };
    using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
    std::vector<Box> boxes;
    boxes.reserve(border.size());
    for (std::size_t e = 0; e < border.size(); ++e) {
        const Vec2 &a = pos[border[e][0]], &b = pos[border[e][1]];
        boxes.emplace_back(CGAL::Bbox_2(std::min(a.x(), b.x()), std::min(a.y(), b.y()), std::max(a.x(), b.x()),
                                        std::max(a.y(), b.y())),
                           e);
    }
    // Closed boxes (CGAL's default) report touching boxes, so touching segments are tested too.
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
        const auto& e = border[x.info()];
        const auto& g = border[y.info()];
        int shared = -1, ea = -1, ga = -1;  // shared vertex, and the other end of each edge
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j)
                if (e[i] == g[j]) {
                    shared = e[i];
                    ea = e[1 - i];
                    ga = g[1 - j];
                }
        if (shared < 0) {
            if (segments_intersect_2d(pos[e[0]], pos[e[1]], pos[g[0]], pos[g[1]])) cross(x.info(), y.info());
            return;
        }
        // Neighbours along the border meet at their shared end; they must not overlap beyond it
        // (collinear and pointing the same way), and neither may have zero length.
        const Vec2 &s = pos[shared], &p = pos[ea], &q = pos[ga];
        if (p == s || q == s) {
            cross(x.info(), y.info());
            return;
        }
        if (orientation_2d(s, p, q) == 0 && sign_of(p.x() - s.x()) == sign_of(q.x() - s.x()) &&
            sign_of(p.y() - s.y()) == sign_of(q.y() - s.y()))
            cross(x.info(), y.info());
    });
    return crossings;
}

Certificate certify(const TexturedMesh& tm, const std::vector<int>& feature_vertex,
                    const std::vector<Vec2>& feature_uv, const CertifyOptions& options) {
    check_shapes(tm);
    if (feature_vertex.size() != feature_uv.size())
        throw BadInput("", std::to_string(feature_vertex.size()) + " feature vertices for " +
                               std::to_string(feature_uv.size()) + " feature UVs");
    const TriMesh& m = tm.mesh;
    const int nf = m.num_faces(), nv = m.num_vertices();
    Certificate c;
    c.triangles = nf;

    // Orientation, exactly, per face; then the majority per chart.
    std::vector<signed char> sign(nf);
    std::unordered_map<int, std::pair<int, int>> per_chart;  // chart -> (positive, negative)
    int last_chart = 0;
    std::pair<int, int>* pn_last = &per_chart[0];  // faces of a chart mostly come together
    for (int f = 0; f < nf; ++f) {
        const Tri& u = tm.uv_faces[f];
        sign[f] = static_cast<signed char>(orientation_2d(tm.uvs[u[0]], tm.uvs[u[1]], tm.uvs[u[2]]));
        const int chart = tm.chart.empty() ? 0 : tm.chart[f];
        if (chart != last_chart) pn_last = &per_chart[last_chart = chart];
        auto& pn = *pn_last;
        if (sign[f] > 0) ++c.positive, ++pn.first;
        if (sign[f] < 0) ++c.negative, ++pn.second;
        if (sign[f] == 0) ++c.degenerate;
    }
    c.mirrored = c.negative > c.positive;
    for (const auto& [chart, pn] : per_chart) c.flipped += std::min(pn.first, pn.second);
    for (int f = 0; f < nf && c.bad_faces.size() < 20; ++f) {
        const auto& pn = per_chart[tm.chart.empty() ? 0 : tm.chart[f]];
        const int majority = pn.first >= pn.second ? 1 : -1;
        if (sign[f] != majority) c.bad_faces.push_back(f);
    }

    // Features: every UV corner of the feature's vertex against the constraint.
    std::vector<int> feature_of(nv, -1);
    for (std::size_t i = 0; i < feature_vertex.size(); ++i) {
        const int v = feature_vertex[i];
        if (v < 0 || v >= nv)
            throw BadInput("", "feature " + std::to_string(i) + " names vertex " + std::to_string(v) + ", but the map has " +
                                   std::to_string(nv) + " vertices");
    }
    // With charts, a feature occurs once per chart (issue 13): each occurrence is compared with
    // the corners of its vertex in its own chart only. Occurrences of one vertex chain through
    // `next_of`.
    const std::vector<int>& occurrence_chart = options.feature_chart;
    if (!occurrence_chart.empty() && occurrence_chart.size() != feature_vertex.size())
        throw BadInput("", std::to_string(occurrence_chart.size()) + " feature charts for " +
                               std::to_string(feature_vertex.size()) + " features");
    std::vector<int> next_of(feature_vertex.size(), -1);
    std::fill(feature_of.begin(), feature_of.end(), -1);
    for (std::size_t i = feature_vertex.size(); i-- > 0;) {
        next_of[i] = feature_of[feature_vertex[i]];
        feature_of[feature_vertex[i]] = int(i);
    }
    std::vector<char> seen(feature_vertex.size(), 0);
    for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k)
            for (int i = feature_of[m.faces[f][k]]; i >= 0; i = next_of[i]) {
                if (!occurrence_chart.empty() && occurrence_chart[i] >= 0 &&
                    occurrence_chart[i] != (tm.chart.empty() ? 0 : tm.chart[f]))
                    continue;
                seen[i] = 1;
                const double e = (tm.uvs[tm.uv_faces[f][k]] - feature_uv[i]).norm();
                if (!(e <= c.feature_max_error)) {  // also catches NaN
                    c.feature_max_error = std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
                    c.worst_feature = int(i);
                }
            }
    for (std::size_t i = 0; i < seen.size(); ++i)
        if (!seen[i])
            throw BadInput("", "feature " + std::to_string(i) + ": vertex " + std::to_string(feature_vertex[i]) +
                                   " is used by no face" +
                                   (occurrence_chart.empty() ? std::string() : " of chart " + std::to_string(occurrence_chart[i])));

    // UV border: canonical UV vertices, edges of exactly one UV face. Built from per-vertex
    // lists rather than hash maps of keys: on a million triangles the hashing was most of the
    // certificate's time.
    std::vector<int> first(nv + 1, 0);  // corners grouped by mesh vertex (counting sort)
    for (const Tri& t : m.faces)
        for (int v : t) ++first[v + 1];
    for (int v = 0; v < nv; ++v) first[v + 1] += first[v];
    std::vector<int> corners(std::size_t(3) * nf), fill(first.begin(), first.end() - 1);
    for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) corners[fill[m.faces[f][k]]++] = 3 * f + k;
    std::vector<Vec2> pos;
    std::vector<int> pos_chart;  // the chart of each UV vertex
    std::vector<std::array<int, 3>> corner_id(nf);
    // Corners in different charts are different UV vertices even where their UVs agree.
    auto uv_bits = [&](int corner) {
        const Vec2& p = tm.uvs[tm.uv_faces[corner / 3][corner % 3]];
        return std::tuple{tm.chart.empty() ? 0 : tm.chart[corner / 3], bits(p.x()), bits(p.y())};
    };
    for (int v = 0; v < nv; ++v) {
        // Corners of one mesh vertex with bitwise equal UVs are one UV vertex.
        auto begin = corners.begin() + first[v], end = corners.begin() + first[v + 1];
        std::sort(begin, end, [&](int a, int b) { return uv_bits(a) < uv_bits(b); });
        for (auto it = begin; it != end; ++it) {
            if (it == begin || uv_bits(*it) != uv_bits(*(it - 1))) {
                pos.push_back(tm.uvs[tm.uv_faces[*it / 3][*it % 3]]);
                pos_chart.push_back(tm.chart.empty() ? 0 : tm.chart[*it / 3]);
            }
            corner_id[*it / 3][*it % 3] = int(pos.size()) - 1;
        }
    }
    // Faces per UV vertex, then every UV edge counted once, from the first face that has it.
    const int nu = int(pos.size());
    std::vector<int> ufirst(nu + 1, 0), ufaces;
    for (const auto& t : corner_id)
        for (int a : t) ++ufirst[a + 1];
    for (int a = 0; a < nu; ++a) ufirst[a + 1] += ufirst[a];
    ufaces.resize(std::size_t(ufirst[nu]));
    std::vector<int> ufill(ufirst.begin(), ufirst.end() - 1);
    for (int f = 0; f < nf; ++f)
        for (int a : corner_id[f]) ufaces[ufill[a]++] = f;
    auto same_edge = [](int a, int b, int x, int y) { return (a == x && b == y) || (a == y && b == x); };
    std::vector<std::array<int, 2>> border;
    std::vector<int> border_degree(pos.size(), 0);
    for (int f = 0; f < nf; ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = corner_id[f][k], b = corner_id[f][(k + 1) % 3];
            bool earlier = false;  // met already, in an earlier face or an earlier corner of f
            for (int j = 0; j < k; ++j) earlier |= same_edge(a, b, corner_id[f][j], corner_id[f][(j + 1) % 3]);
            int n = 0, previous = -1;
            for (int i = ufirst[a]; i < ufirst[a + 1] && !earlier; ++i) {
                const int g = ufaces[i];
                if (g == previous) continue;  // a face listed twice (a repeated corner)
                previous = g;
                for (int j = 0; j < 3; ++j)
                    if (same_edge(a, b, corner_id[g][j], corner_id[g][(j + 1) % 3])) {
                        if (g < f) earlier = true;
                        ++n;
                    }
            }
            if (earlier) continue;
            if (n > 2) ++c.border_crossings;  // a UV edge of three or more faces: the UV surface folds onto itself
            if (n != 1) continue;
            border.push_back({a, b});
            ++border_degree[a];
            ++border_degree[b];
        }
    // A UV vertex with more than two border edges pinches the border: it touches itself there.
    for (int deg : border_degree)
        if (deg > 2) ++c.border_crossings;
    c.border_edges = int(border.size());

    // Charts each have their own UV square (their own image): their borders are tested apart.
    std::map<int, std::vector<std::array<int, 2>>> border_of_chart;
    for (const auto& e : border) border_of_chart[pos_chart[e[0]]].push_back(e);
    for (const auto& [chart, edges] : border_of_chart) c.border_crossings += count_border_crossings(pos, edges);
    c.border_simple = c.border_crossings == 0;

    if (options.distortion) c.distortion = measure_distortion(tm);
    c.valid = c.flipped == 0 && c.degenerate == 0 && c.feature_max_error == 0 && c.border_simple;
    return c;
}

nlohmann::json certificate_to_json(const Certificate& c) {
    nlohmann::json j;
    j["valid"] = c.valid;
    j["flipped"] = c.flipped;
    j["degenerate"] = c.degenerate;
    j["feature_max_error"] = c.feature_max_error;
    j["border_simple"] = c.border_simple;
    j["triangles"] = c.triangles;
    j["mirrored"] = c.mirrored;
    j["border_edges"] = c.border_edges;
    j["border_crossings"] = c.border_crossings;
    j["worst_feature"] = c.worst_feature;
    const Distortion& d = c.distortion;
    // nlohmann::json writes non-finite numbers as null, which is what a degenerate map should show.
    j["symmetric_dirichlet"] = d.symmetric_dirichlet;
    j["conformal_mean"] = d.conformal_mean;
    j["conformal_max"] = d.conformal_max;
    j["area_distortion_mean"] = d.area_mean;
    j["area_distortion_max"] = d.area_max;
    j["l2_stretch"] = d.l2_stretch;
    return j;
}

}  // namespace ctmap
