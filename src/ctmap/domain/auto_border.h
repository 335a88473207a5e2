#pragma once
/// \file auto_border.h
/// The automatic border (issue 12, beyond paper §2.2): the paper's border is a polygon of
/// straight sides through border features, so landmark-only sets (no feature on the mesh border)
/// and layouts whose interior features lie outside the straight polygon of the given border
/// features have no border. Here ctmap places border features itself, on border vertices of the
/// mesh, so that the exact pipeline (§2.3-2.4) runs as for a user's own border.
///
/// How: a least squares conformal map of the mesh with the features pinned at their UVs (with a
/// single feature: Tutte's map, domain/starter_features.h, moved onto it by a similarity) gives
/// where the mesh border would lie in the image; whether the image is mirrored comes from the
/// given border features' polygon, or else from which of the similarity and the mirror
/// similarity fits Tutte's map to the features better. The region R = the convex hull of that fitted border and of a margin around every
/// feature, clipped to the image, bounds the new border. The border polygon is star-shaped around
/// a centre c inside R: the given border features where they are, each with a narrow notch
/// reaching out to ∂R, and between them the added ones on ∂R at angles that follow the mesh
/// border's arc length. Strictly increasing angles around c make the polygon simple, in the mesh
/// border's cyclic order; every interior feature is then checked (exact predicates) to lie
/// strictly inside.
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Options of `place_border_features`.
struct AutoBorderOptions {
    /// About how many border features to place around the whole border (fewer if the mesh
    /// border has fewer vertices; doubled while an interior feature is not strictly inside).
    int samples = 32;
    /// How far (UV units: the image is [0, 1]^2) the border keeps from every feature, less where
    /// the image's edge is closer.
    double margin = 0.03;
};

/// What `place_border_features` added.
struct AutoBorder {
    std::string reason;        ///< why border features were needed ("" when none were)
    std::vector<std::string> name;  ///< per added feature: its name (map_texture: auto_border_1, ...)
    std::vector<int> vertex;   ///< per added feature: its mesh vertex (on the mesh border)
    std::vector<Vec2> uv;      ///< per added feature: its UV, inside [0, 1]^2
    bool mirrored = false;     ///< the border runs clockwise in the image (a mirrored chart)
};

/// Why the features need an automatic border: "" if at least 3 features lie on the mesh border
/// and every interior feature lies strictly inside their polygon, or if that polygon is not
/// simple (an order mismatch is the user's to fix: `triangulate_features` reports it).
/// \param border border features (indices into `uv`) in the mesh border's order.
/// \pre uv finite; `border` indices valid.
std::string auto_border_reason(const std::vector<Vec2>& uv, const std::vector<int>& border,
                               const std::vector<std::string>& names);

/// Places border features on border vertices of `mesh` for the features (`feature_vertex[i]`,
/// `uv[i]`) when `auto_border_reason` gives a reason; returns nothing added otherwise.
/// The given border features keep their UVs; the added ones follow them in the mesh border's
/// cyclic order, and with them every interior feature lies strictly inside the border polygon,
/// which is simple and inside [0, 1]^2.
/// \pre `mesh` is a manifold disc; feature vertices distinct and in range; UVs finite, distinct,
///      in [0, 1]^2.
/// \throw BadInput naming the file if no such border can be placed (a feature on the image's
///        edge that is not on the mesh border, given border features whose order no star-shaped
///        border can follow, too few border vertices between two given border features).
AutoBorder place_border_features(const TriMesh& mesh, const std::vector<int>& feature_vertex,
                                 const std::vector<Vec2>& uv, const std::vector<std::string>& names,
                                 const AutoBorderOptions& options = {});

}  // namespace ctmap
