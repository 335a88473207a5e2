#pragma once
/// \file starter_charts.h
/// A feasible two-chart features file for a closed mesh (issue 13; paper §3: Igea's two photos
/// meet on its bisection line; the rabbit's photo and its mirror image): a seam of features round
/// the mesh's middle, each half placed in its image by a one-to-one map of the disc.
#include <string>
#include <vector>

#include "ctmap/domain/starter_features.h"
#include "ctmap/io/chart_features.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Options of `starter_charts`.
struct StarterChartsOptions {
    int seam = 8;         ///< features on the seam (bisection_seam_vertices)
    int interior = 12;    ///< interior landmarks per chart
    bool mirror = true;   ///< the second chart's image is the first's mirror image (x -> W - x)
    double margin = 0.05;
};

/// Two charts, "front" and "back", on `width` x `height` images: the seam features (seam0, ...)
/// in both, each chart's landmarks spread over its half (front_landmark0, ...), image points from
/// each half's Tutte map spread by area (a valid map of both charts exists). With `mirror`, the
/// back chart's points are mirrored (its image is the mirror image of the front's).
/// \pre `mesh` is a consistently oriented closed manifold of genus 0.
/// \throw BadInput if the seam does not cut the mesh into two discs (a mesh with handles).
std::vector<ChartFeatures> starter_charts(const TriMesh& mesh, int width, int height,
                                          const StarterChartsOptions& options = {});

/// One chart round a patch of a mesh that is not a disc (closed, several border loops, handles):
/// the disc of faces within a geodesic-like distance (along edges) of a seed vertex (the vertex
/// farthest along +z, the front in the OBJ convention) holding about `area_share` of the
/// surface, shrunk until it is a disc; `starter_features` on it (its border features equally
/// spaced round it, named border0, ... in order, landmarks inside). The rest of the mesh is what
/// `map_charts` maps automatically. \pre `mesh` is a consistently oriented manifold, 0 <
/// area_share < 1. \throw BadInput if no disc round the seed is found.
ChartFeatures starter_patch_chart(const TriMesh& mesh, int width, int height, double area_share,
                                  const StarterOptions& options = {});

/// A features file with charts as JSON text (DESIGN §4, issue 13), image points in pixels.
std::string chart_features_to_json(const std::vector<ChartFeatures>& charts);

}  // namespace ctmap
