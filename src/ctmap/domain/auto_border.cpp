#include "ctmap/domain/auto_border.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/convex_hull_2.h>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <complex>

#include "ctmap/border_loop.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/errors.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = K::Point_2;
using Cx = std::complex<double>;

P2 point(const Vec2& v) { return P2(v.x(), v.y()); }
double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

std::vector<P2> polygon(const std::vector<Vec2>& uv, const std::vector<int>& order) {
    std::vector<P2> poly;
    for (int i : order) poly.push_back(point(uv[i]));
    return poly;
}

/// Interior features among the first `count` (those not in `border`) not strictly inside the
/// polygon of `border`.
std::vector<int> outside(const std::vector<Vec2>& uv, const std::vector<int>& border, std::size_t count) {
    const std::vector<P2> poly = polygon(uv, border);
    std::vector<char> on(uv.size(), 0);
    for (int b : border) on[b] = 1;
    std::vector<int> out;
    for (std::size_t i = 0; i < count; ++i)
        if (!on[i] && CGAL::bounded_side_2(poly.begin(), poly.end(), point(uv[i]), K()) != CGAL::ON_BOUNDED_SIDE)
            out.push_back(int(i));
    return out;
}

/// The convex polygon `poly` (counter-clockwise) clipped to the image inset by `inset` on every
/// side, [inset, 1 - inset]^2 (Sutherland-Hodgman); points on a clipping line get its coordinate
/// exactly.
std::vector<Vec2> clip_to_image(std::vector<Vec2> poly, double inset) {
    const double lo = inset, hi = 1 - inset;
    for (int axis = 0; axis < 2; ++axis)
        for (double edge : {lo, hi}) {
            auto in = [&](const Vec2& p) { return edge == lo ? p[axis] >= lo : p[axis] <= hi; };
            std::vector<Vec2> out;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const Vec2& a = poly[i];
                const Vec2& b = poly[(i + 1) % poly.size()];
                if (in(a)) out.push_back(a);
                if (in(a) != in(b)) {
                    const double t = (edge - a[axis]) / (b[axis] - a[axis]);
                    Vec2 x = a + t * (b - a);
                    x[axis] = edge;
                    x[1 - axis] = std::clamp(x[1 - axis], lo, hi);
                    out.push_back(x);
                }
            }
            poly = std::move(out);
        }
    return poly;
}

/// The point of the convex region `r` (counter-clockwise, `c` strictly inside) where the ray
/// from `c` at `angle` leaves it.
Vec2 ray_exit(const std::vector<Vec2>& r, const Vec2& c, double angle) {
    const Vec2 d(std::cos(angle), std::sin(angle));
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < r.size(); ++i) {
        const Vec2& a = r[i];
        const Vec2 e = r[(i + 1) % r.size()] - a;
        const double den = cross(d, e);
        if (std::abs(den) < 1e-300) continue;
        const double t = cross(a - c, e) / den, s = cross(a - c, d) / den;
        if (t > 0 && s >= -1e-12 && s <= 1 + 1e-12) best = std::min(best, t);
    }
    const Vec2 p = c + best * d;
    return Vec2(std::clamp(p.x(), 0.0, 1.0), std::clamp(p.y(), 0.0, 1.0));
}

/// Distance from `c` to the nearest side of the convex region `r` (negative outside).
double depth(const std::vector<Vec2>& r, const Vec2& c) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < r.size(); ++i) {
        const Vec2 e = r[(i + 1) % r.size()] - r[i];
        if (e.norm() > 0) d = std::min(d, cross(e, c - r[i]) / e.norm());
    }
    return d;
}

double wrap(double a) {  // into [0, 2 pi)
    a = std::fmod(a, 2 * M_PI);
    return a < 0 ? a + 2 * M_PI : a;
}

/// The similarity z -> a z + b (z conjugated when `mirror`) that best fits the Tutte points of
/// the features to their UVs, and its squared residual.
struct Fit {
    Cx a{0.45, 0}, b{0.5, 0.5};
    bool mirror = false;
    double residual = 0;
    Cx at(const Vec2& t) const { return a * (mirror ? Cx(t.x(), -t.y()) : Cx(t.x(), t.y())) + b; }
};

Fit fit_similarity(const std::vector<Vec2>& tutte, const std::vector<int>& fv, const std::vector<Vec2>& uv, bool mirror) {
    Fit f;
    f.mirror = mirror;
    const int n = int(uv.size());
    Cx tm(0, 0), pm(0, 0);
    std::vector<Cx> t(n), p(n);
    for (int i = 0; i < n; ++i) {
        const Vec2& q = tutte[fv[i]];
        t[i] = mirror ? Cx(q.x(), -q.y()) : Cx(q.x(), q.y());
        p[i] = Cx(uv[i].x(), uv[i].y());
        tm += t[i] / double(n);
        pm += p[i] / double(n);
    }
    double stt = 0;
    Cx stp(0, 0);
    for (int i = 0; i < n; ++i) {
        stt += std::norm(t[i] - tm);
        stp += std::conj(t[i] - tm) * (p[i] - pm);
    }
    // One feature, or all at one Tutte point: the disc at the starter features' size.
    if (stt > 1e-12 && std::abs(stp / stt) > 1e-9) f.a = stp / stt;
    f.b = pm - f.a * tm;
    for (int i = 0; i < n; ++i) f.residual += std::norm(f.a * t[i] + f.b - p[i]);
    return f;
}

/// Least squares conformal map (Lévy et al. 2002) of `mesh` with the features pinned at their
/// UVs (x negated when `mirror`, and back: a conformal map cannot mirror): where the mesh border
/// would lie if the features alone decided the map. Needs two or more features; empty if the
/// solve fails. Per face, in a local frame z of its 3D triangle, the Cauchy-Riemann residual
/// sum_j (z_{j+2} - z_{j+1}) U_j / sqrt(area) is a complex row; free rows are solved in the
/// least-squares sense (normal equations, sparse LDL^T).
std::vector<Vec2> pinned_lscm(const TriMesh& mesh, const std::vector<int>& fv, const std::vector<Vec2>& uv, bool mirror) {
    const int nv = mesh.num_vertices();
    std::vector<int> pin(nv, -1), index(nv, -1);
    for (std::size_t i = 0; i < fv.size(); ++i) pin[fv[i]] = int(i);
    int m = 0;
    for (int v = 0; v < nv; ++v)
        if (pin[v] < 0) index[v] = m++;
    auto pinned = [&](int v) { return Cx(mirror ? -uv[pin[v]].x() : uv[pin[v]].x(), uv[pin[v]].y()); };
    std::vector<Eigen::Triplet<double>> trip;
    std::vector<double> rhs_re, rhs_im;
    int rows = 0;
    for (const Tri& t : mesh.faces) {
        const Vec3 &p0 = mesh.positions[t[0]], &p1 = mesh.positions[t[1]], &p2 = mesh.positions[t[2]];
        const Vec3 e1 = p1 - p0, e2 = p2 - p0, n = e1.cross(e2);
        const double area2 = n.norm();
        if (!(area2 > 0) || !(e1.norm() > 0)) continue;
        const Vec3 x = e1 / e1.norm(), y = n.cross(x) / area2;
        const Cx z[3] = {Cx(0, 0), Cx(e1.norm(), 0), Cx(e2.dot(x), e2.dot(y))};
        const double w = 1 / std::sqrt(0.5 * area2);
        Cx known(0, 0);
        for (int j = 0; j < 3; ++j) {
            const Cx W = w * (z[(j + 2) % 3] - z[(j + 1) % 3]);
            const int v = t[j];
            if (pin[v] >= 0) {
                known += W * pinned(v);
                continue;
            }
            // W U = (a u - b v) + i (a v + b u): u in column index, v in column m + index.
            trip.emplace_back(rows, index[v], W.real());
            trip.emplace_back(rows, m + index[v], -W.imag());
            trip.emplace_back(rows + 1, index[v], W.imag());
            trip.emplace_back(rows + 1, m + index[v], W.real());
        }
        rhs_re.push_back(-known.real());
        rhs_im.push_back(-known.imag());
        rows += 2;
    }
    Eigen::SparseMatrix<double> A(rows, 2 * m);
    A.setFromTriplets(trip.begin(), trip.end());
    Eigen::VectorXd b(rows);
    for (int r = 0; r < rows / 2; ++r) b[2 * r] = rhs_re[r], b[2 * r + 1] = rhs_im[r];
    const Eigen::SparseMatrix<double> M = A.transpose() * A;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(M);
    if (solver.info() != Eigen::Success) return {};
    const Eigen::VectorXd x = solver.solve(A.transpose() * b);
    if (solver.info() != Eigen::Success || !x.allFinite()) return {};
    std::vector<Vec2> out(nv);
    for (int v = 0; v < nv; ++v) {
        const Cx u = pin[v] >= 0 ? pinned(v) : Cx(x[index[v]], x[m + index[v]]);
        out[v] = Vec2(mirror ? -u.real() : u.real(), u.imag());
    }
    return out;
}

}  // namespace

std::string auto_border_reason(const std::vector<Vec2>& uv, const std::vector<int>& border,
                               const std::vector<std::string>& names) {
    if (border.empty()) return "no feature lies on the mesh border";
    if (border.size() < 3) return "only " + std::to_string(border.size()) + " feature(s) lie on the mesh border";
    const std::vector<P2> poly = polygon(uv, border);
    if (!CGAL::is_simple_2(poly.begin(), poly.end(), K())) return "";
    const std::vector<int> out = outside(uv, border, uv.size());
    if (out.empty()) return "";
    std::string list;
    for (int i : out) list += (list.empty() ? "" : ", ") + feature_label(names, i);
    return "interior feature(s) " + list + " outside the straight polygon of the border features";
}

AutoBorder place_border_features(const TriMesh& mesh, const std::vector<int>& fv, const std::vector<Vec2>& uv,
                                 const std::vector<std::string>& names, const AutoBorderOptions& opt) {
    const std::vector<int> loop = border_loop(mesh);
    const int nl = int(loop.size()), n = int(uv.size());
    std::vector<int> at(mesh.num_vertices(), -1);
    for (int i = 0; i < nl; ++i) at[loop[i]] = i;
    std::vector<int> given;  // the given border features, in loop order
    for (int i = 0; i < n; ++i)
        if (at[fv[i]] >= 0) given.push_back(i);
    std::sort(given.begin(), given.end(), [&](int a, int b) { return at[fv[a]] < at[fv[b]]; });
    AutoBorder out;
    out.reason = auto_border_reason(uv, given, names);
    if (out.reason.empty()) return out;
    const int k = int(given.size());
    if (n == 0) throw BadInput("", "no features: at least one is needed");
    for (int i = 0; i < n; ++i)
        if (at[fv[i]] < 0 && (uv[i].x() <= 0 || uv[i].x() >= 1 || uv[i].y() <= 0 || uv[i].y() >= 1))
            throw BadInput("", "feature " + feature_label(names, i) + " lies on the image's edge but not on the mesh "
                                 "border: no border inside the image can hold it (move it inside, or mark a border vertex there)");

    // The orientation: the given border polygon's (3 or more), else whichever of the similarity
    // and the mirror similarity fits Tutte's map to the features better by more than rounding
    // (with one or two features, or collinear ones, both fit exactly: not mirrored).
    std::vector<Vec2> tutte;  // Tutte's map, solved only where it is used (a sparse solve)
    auto tutte_fit = [&](bool mirrored) {
        if (tutte.empty()) tutte = tutte_map(mesh);
        return fit_similarity(tutte, fv, uv, mirrored);
    };
    bool mirror = false;
    if (k >= 3) {
        // (orientation_2 needs a simple polygon; crossing given border features are refused by
        // triangulate_features with their names.)
        const std::vector<P2> poly = polygon(uv, given);
        mirror = CGAL::is_simple_2(poly.begin(), poly.end(), K()) &&
                 CGAL::orientation_2(poly.begin(), poly.end(), K()) == CGAL::CLOCKWISE;
    } else if (n > 2) {
        double spread = 0;
        Vec2 mean = Vec2::Zero();
        for (const Vec2& p : uv) mean += p / n;
        for (const Vec2& p : uv) spread += (p - mean).squaredNorm();
        mirror = tutte_fit(true).residual < tutte_fit(false).residual - 1e-9 * spread;
    }
    const double sigma = mirror ? -1 : 1;
    out.mirrored = mirror;

    // Where the mesh border would lie: the pinned LSCM map with two features or more (conformal,
    // so the features' layout sets its size and turn), else Tutte's map fitted to the feature.
    std::vector<Vec2> fitted;
    if (n >= 2) {
        const std::vector<Vec2> lscm = pinned_lscm(mesh, fv, uv, mirror);
        if (!lscm.empty())
            for (int v : loop) fitted.push_back(lscm[v]);
    }
    if (fitted.empty()) {
        const Fit fit = tutte_fit(mirror);
        for (int v : loop) {
            const Cx z = fit.at(tutte[v]);
            fitted.emplace_back(z.real(), z.imag());
        }
    }

    // R: the hull of the fitted border and of a margin around every feature, in the image.
    std::vector<P2> cloud, hull;
    for (const Vec2& p : fitted) cloud.push_back(point(p));
    for (const Vec2& p : uv)
        for (int j = 0; j < 8; ++j)
            cloud.emplace_back(p.x() + opt.margin * std::cos(M_PI * j / 4), p.y() + opt.margin * std::sin(M_PI * j / 4));
    CGAL::convex_hull_2(cloud.begin(), cloud.end(), std::back_inserter(hull), K());
    std::vector<Vec2> region;
    for (const P2& p : hull) region.emplace_back(p.x(), p.y());
    // Inset from the image's edges: a border vertex on (or a hair from) the image's edge would
    // be frozen there, or pressed by the free border's barrier, in the optimiser. The inset is a
    // hundredth of the image, less where a feature off the mesh border is closer to the edge.
    double inset = 0.01;
    for (int i = 0; i < n; ++i)
        if (at[fv[i]] < 0)
            inset = std::min({inset, 0.5 * uv[i].x(), 0.5 * uv[i].y(), 0.5 * (1 - uv[i].x()), 0.5 * (1 - uv[i].y())});
    region = clip_to_image(region, inset);
    if (region.size() < 3) throw BadInput("", out.reason + ", and no region inside the image can hold the border");

    // Arc length along the loop from loop[0], for the added features' angles.
    std::vector<double> arc(nl + 1, 0);
    for (int i = 0; i < nl; ++i) arc[i + 1] = arc[i] + (mesh.positions[loop[(i + 1) % nl]] - mesh.positions[loop[i]]).norm();
    auto arc_between = [&](int from, int to) {  // along the loop, from index `from` forward to `to`
        return to > from ? arc[to] - arc[from] : arc[to] - arc[from] + arc[nl];
    };

    std::vector<Vec2> centres;
    {
        Vec2 all = Vec2::Zero(), inner = Vec2::Zero(), mid = Vec2::Zero();
        int ni = 0;
        for (int i = 0; i < n; ++i) {
            all += uv[i] / n;
            if (at[fv[i]] < 0) inner += uv[i], ++ni;
        }
        for (const Vec2& p : region) mid += p / double(region.size());
        Vec2 middle = Vec2::Zero();
        for (const Vec2& p : fitted) middle += p / double(fitted.size());
        centres = {all, mid, middle};
        if (ni > 0) centres.insert(centres.begin() + 1, inner / ni);
        for (int j = 0; j < 8; ++j) centres.push_back(all + 0.05 * Vec2(std::cos(0.7 + j), std::sin(0.7 + j)));
    }
    for (const Vec2& c : centres) {
        if (!(depth(region, c) > 1e-6)) continue;
        std::vector<double> theta(n, 0);
        bool centred = true;
        for (int i = 0; i < n; ++i) {
            theta[i] = std::atan2(uv[i].y() - c.y(), uv[i].x() - c.x());
            if (at[fv[i]] >= 0 && (uv[i] - c).norm() < 1e-9) centred = false;
        }
        if (!centred) continue;
        // The given border features must turn once around c in the border's sense.
        std::vector<double> gap(k, 2 * M_PI);
        double turn = 0;
        for (int j = 0; j < k && k > 1; ++j) {
            gap[j] = wrap(sigma * (theta[given[(j + 1) % k]] - theta[given[j]]));
            turn += gap[j];
        }
        if (k > 1 && (std::abs(turn - 2 * M_PI) > 1e-9 || *std::min_element(gap.begin(), gap.end()) <= 0)) continue;
        // Each given border feature's notch: half as wide as the angle to the nearest feature.
        std::vector<double> notch(k, 0.2);
        for (int j = 0; j < k; ++j) {
            const int b = given[j];
            notch[j] = std::min({notch[j], 0.25 * gap[j], 0.25 * gap[(j + k - 1) % k]});
            for (int i = 0; i < n; ++i)
                if (i != b && (uv[i] - c).norm() > 1e-12) {
                    const double d = wrap(theta[i] - theta[b]);
                    notch[j] = std::min(notch[j], 0.5 * std::min(d, 2 * M_PI - d));
                }
        }
        if (k > 0 && !(*std::min_element(notch.begin(), notch.end()) > 1e-9)) continue;

        double phase = 0;  // with no given border feature: the fitted map's rotation around c
        if (k == 0) {
            Cx sum(0, 0);
            for (int i = 0; i < nl; ++i) {
                const Vec2& z = fitted[i];
                const double a = std::atan2(z.y() - c.y(), z.x() - c.x()) - sigma * 2 * M_PI * arc[i] / arc[nl];
                sum += std::polar(1.0, a);
            }
            phase = std::arg(sum);
        }
        for (int samples = std::max(3, opt.samples);; samples *= 2) {
            AutoBorder tried = out;
            tried.vertex.clear();
            tried.uv.clear();
            std::vector<int> order;  // feature indices (given, then added as n + j) in loop order
            // The added features along the loop from loop index `from` (exclusive) over `span`
            // loop steps, `count` of them spread by index, at angles from `a0` to `a1` by arc.
            auto add = [&](int from, int span, int count, double a0, double a1) {
                const int free = span - 1;
                count = std::min(count, free);
                if (count <= 0) return;
                std::vector<int> pick;
                for (int j = 0; j < count; ++j)
                    pick.push_back(count == 1 ? free / 2 : int(std::lround(double(j) * (free - 1) / (count - 1))));
                const int first = (from + 1 + pick.front()) % nl, last = (from + 1 + pick.back()) % nl;
                const double s0 = arc_between(from, first), s1 = arc_between(from, last);
                for (int p : pick) {
                    const int li = (from + 1 + p) % nl;
                    const double s = arc_between(from, li);
                    const double w = count == 1 || s1 <= s0 ? 0.5 : (s - s0) / (s1 - s0);
                    tried.vertex.push_back(loop[li]);
                    tried.uv.push_back(ray_exit(region, c, a0 + w * (a1 - a0)));
                    order.push_back(n + int(tried.vertex.size()) - 1);
                }
            };
            if (k == 0) {
                const int count = std::min(samples, nl);
                for (int j = 0; j < count; ++j) {
                    const int li = int(std::lround(double(j) * nl / count)) % nl;
                    tried.vertex.push_back(loop[li]);
                    tried.uv.push_back(ray_exit(region, c, phase + sigma * 2 * M_PI * arc[li] / arc[nl]));
                    order.push_back(n + j);
                }
            } else {
                for (int j = 0; j < k; ++j) {
                    const int b = given[j], next = given[(j + 1) % k];
                    order.push_back(b);
                    const int from = at[fv[b]];
                    int span = at[fv[next]] - from;
                    if (span <= 0) span += nl;
                    const double a0 = theta[b] + sigma * notch[j];
                    const double a1 = theta[b] + sigma * (gap[j] - notch[(j + 1) % k]);
                    add(from, span, int(std::ceil(samples * gap[j] / (2 * M_PI))) + 1, a0, a1);
                }
            }
            std::vector<Vec2> all = uv;
            all.insert(all.end(), tried.uv.begin(), tried.uv.end());
            const std::vector<P2> poly = polygon(all, order);
            if (order.size() >= 3 && CGAL::is_simple_2(poly.begin(), poly.end(), K()) &&
                outside(all, order, uv.size()).empty())
                return tried;
            if (samples >= 2 * nl) break;
        }
    }
    throw BadInput("", out.reason + ", and ctmap could not place border features around them (the given border "
                                      "features' order around the others, or too few border vertices between two "
                                      "of them); give border features yourself, or use --border given to see the "
                                      "straight-border rules");
}

}  // namespace ctmap
