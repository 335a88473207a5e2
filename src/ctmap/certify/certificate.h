#pragma once
/// \file certificate.h
/// The validity certificate of a texture map (DESIGN §3 "Valid map"): exact orientation of every
/// UV triangle, exact feature positions, a simple UV border, and the usual distortion measures.
/// The decisions use exact predicates (CGAL's Epick kernel, kept inside certificate.cpp), so a
/// map that passes is valid for every reader that uses the same doubles.
#include <nlohmann/json.hpp>
#include <array>
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Exact sign of the orientation of the UV triangle (a, b, c): +1 counter-clockwise, -1
/// clockwise, 0 collinear. Exact for every finite double input (CGAL Epick, filtered).
int orientation_2d(const Vec2& a, const Vec2& b, const Vec2& c);

/// Exact test whether the closed segments [a, b] and [c, d] share at least one point.
bool segments_intersect_2d(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d);

/// A feature's UV from its image point in pixels (DESIGN §3): (x / W, 1 - y / H). The one
/// definition shared by `ctmap map` (which writes it) and `ctmap check` (which compares with it),
/// so that "exact" means bitwise.
inline Vec2 image_to_uv(const Vec2& pixel, int width, int height) {
    return Vec2(pixel.x() / width, 1.0 - pixel.y() / height);
}

/// Distortion of the map from the surface to the UV plane, after scaling the UVs so that the UV
/// area equals the 3D area (so that 1 is ideal for every measure). Per face, sigma1 >= sigma2
/// are the singular values of the Jacobian from the face's 3D plane to UV. Means are weighted
/// by 3D area; faces of zero 3D area are left out. A degenerate UV face makes the measures
/// infinite (written as null in JSON).
struct Distortion {
    double symmetric_dirichlet = 0;  ///< mean of s1^2 + s2^2 + s1^-2 + s2^-2 (4 for an isometry)
    double conformal_mean = 0;       ///< mean of s1 / s2 (1 for a conformal map)
    double conformal_max = 0;
    double area_mean = 0;            ///< mean of max(s1 s2, 1 / (s1 s2)) (1 for an area-preserving map)
    double area_max = 0;
    double l2_stretch = 0;           ///< Sander et al. 2001 L2 stretch, sqrt(mean of (s1^-2 + s2^-2) / 2)
    int faces_measured = 0;
};

/// The pairs of border edges (`border`: indices into `pos`, each edge once) that cross or touch
/// where they must not: two edges sharing no end that meet, neighbours sharing an end that
/// overlap beyond it (collinear, pointing the same way), and edges of zero length. Exact
/// predicates after a box-intersection filter, O(n log n). 0 means the border is simple, given
/// that no vertex has more than two border edges (the caller checks that). With `pairs`, the
/// indices (into `border`) of each offending pair are appended to it.
int count_border_crossings(const std::vector<Vec2>& pos, const std::vector<std::array<int, 2>>& border,
                           std::vector<std::array<int, 2>>* pairs = nullptr);

/// The certificate of one map.
struct Certificate {
    bool valid = false;              ///< 0 flipped, 0 degenerate, feature error 0, border simple
    int triangles = 0;
    int positive = 0;                ///< counter-clockwise UV triangles
    int negative = 0;                ///< clockwise UV triangles
    int flipped = 0;                 ///< per chart, the triangles of the minority orientation
    int degenerate = 0;              ///< UV triangles of zero area (exactly) or with a repeated corner
    bool mirrored = false;           ///< the majority orientation is clockwise (allowed, DESIGN §3)
    double feature_max_error = 0;    ///< max over features and their UV corners of |uv - constraint|
    int worst_feature = -1;          ///< index of the feature with the largest error (-1: none wrong)
    bool border_simple = false;      ///< no two UV border edges cross or touch except neighbours at their shared end
    int border_edges = 0;
    int border_crossings = 0;        ///< pairs of UV border edges that cross or touch where they must not
    std::vector<int> bad_faces;      ///< the first flipped or degenerate faces (at most 20), for messages
    Distortion distortion;
};

/// Options of `certify`.
struct CertifyOptions {
    bool distortion = true;  ///< compute the distortion measures (the validity part is always computed)
    /// With several charts (issue 13), per feature entry the chart whose corners it is compared
    /// with (a feature on a seam is one entry per chart, each with that chart's UV); -1 or empty:
    /// every corner of the vertex.
    std::vector<int> feature_chart;
};

/// Certifies the texture map `tm` with the features at vertices `feature_vertex` whose UVs must
/// be exactly `feature_uv` (every UV corner of the vertex is compared).
/// Orientation: every UV triangle by the exact predicate; within each chart the majority sign is
/// the chart's (a mirrored chart is allowed, a mix is not), the minority counts as flipped.
/// Border: the UV border edges (edges of one UV face; corners of one mesh vertex with bitwise
/// equal UVs in one chart count as one UV vertex, so files that repeat `vt` per face are read
/// right) are tested pairwise within each chart (charts have their own images) with exact predicates after a box-intersection filter (O(n log n)); an edge
/// shared by more than two UV faces counts as a crossing.
/// \pre feature_vertex.size() == feature_uv.size(); uv_faces has one entry per face.
/// \throw BadInput if a feature vertex is out of range or used by no face, or uv_faces/chart
///        do not match the faces.
Certificate certify(const TexturedMesh& tm, const std::vector<int>& feature_vertex,
                    const std::vector<Vec2>& feature_uv, const CertifyOptions& options = {});

/// Distortion measures alone (see `Distortion`), for maps that are not certified (e.g. during
/// refinement). \pre as `certify`.
Distortion measure_distortion(const TexturedMesh& tm);

/// The certificate as JSON: valid, flipped, degenerate, feature_max_error, border_simple,
/// triangles, mirrored, border_edges, border_crossings, worst_feature, and the distortion keys
/// symmetric_dirichlet, conformal_mean, conformal_max, area_distortion_mean,
/// area_distortion_max, l2_stretch (infinite values as null).
nlohmann::json certificate_to_json(const Certificate& c);

}  // namespace ctmap
