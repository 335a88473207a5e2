#pragma once
/// \file map_charts.h
/// Constrained texture mapping with several charts (issue 13; paper §3, Figs. 5-7): each chart
/// has its own image; the mesh is cut along the charts' borders (seams) into one disc per chart,
/// each disc goes through `map_texture`, and the charts come back together as one mesh with UVs
/// per face corner, a seam vertex carrying one UV per chart.
#include <string>
#include <vector>

#include "ctmap/cut/chart_regions.h"
#include "ctmap/map_texture.h"

namespace ctmap {

/// One chart for `map_charts`: its features with their UVs in this chart (DESIGN §3) and its
/// border features' names in order around its image polygon (either direction). A feature in
/// several charts has the same `vertex` or `point` in each.
struct ChartInput {
    std::string name;
    std::vector<MapFeature> features;
    std::vector<std::string> border;  ///< empty only for a lone chart bounded by the mesh border
};

/// One chart's map.
struct ChartMap {
    std::string name;
    MapResult result;         ///< the map of the chart's region (`result.cut.mesh` is the region, refined)
    std::vector<int> vertex;  ///< per vertex of result.cut.mesh, its vertex in ChartsResult::textured.mesh
    std::vector<int> faces;   ///< the faces of ChartsResult::textured.mesh that are this chart's
};

/// A feature's place in one chart: feature occurrences (feature, chart, UV), so that a seam
/// feature has one UV per chart.
struct FeatureOccurrence {
    std::string name;
    int chart = 0;
    int vertex = -1;  ///< of ChartsResult::textured.mesh
    Vec2 uv{0, 0};
};

/// The faces in no chart, mapped automatically (issue 13): chart `charts.size()` of the result.
struct RestMap {
    int faces = 0;       ///< faces in no chart (0: the charts cover the mesh; no rest chart)
    int pieces = 0;      ///< connected pieces, each cut into a disc with a tile of its own
    int cut_edges = 0;   ///< edges cut open to make the pieces discs (handles, several border loops)
    int iterations = 0;  ///< the optimiser's iterations over the pieces
};

/// The charts' maps together, certified.
struct ChartsResult {
    /// The whole mesh: its first vertices are the input's, in order (DESIGN §3), then the point
    /// features, then what each chart's cut inserted; UVs per face corner, a chart id per face,
    /// faces grouped by chart and, within a chart, by patch.
    TexturedMesh textured;
    std::vector<ChartMap> charts;
    std::vector<FeatureOccurrence> occurrences;
    std::vector<std::vector<int>> seams;  ///< the seam pieces as vertex paths of textured.mesh
    int seams_rerouted = 0;               ///< pieces traced again round a feature (chart_regions)
    Certificate certificate;              ///< of the whole map, per chart (certify's feature_chart)
    MapTimings timings_ms;                ///< summed over the charts, plus the seams in `paths`
    RestMap rest;                         ///< the faces in no chart

    /// The occurrences as certify's arguments.
    std::vector<int> occurrence_vertices() const;
    std::vector<Vec2> occurrence_uvs() const;
    std::vector<int> occurrence_charts() const;
};

/// Maps `mesh` with several charts (paper §3): the seams first (cut/chart_regions.h), then each
/// chart's region by `map_texture` with `options`, then the whole certified: every chart one
/// orientation, every occurrence exact, every chart's UV border simple.
/// Faces in no chart's region (the back of a head, a mesh's other handles and borders) are mapped
/// automatically as one more chart, `charts.size()`: each connected piece cut into a disc through
/// its handles and between its border loops, mapped one-to-one onto a circle (Tutte), optimised,
/// and placed in a tile of its own of the unit square.
/// The charts are mapped in parallel (TBB) and put together in chart order, so the result does
/// not depend on the threads; `options.progress` then reports one stage, "charts" (done of
/// total), from one thread at a time, and any other callback in `options` may be called from
/// several threads at once.
/// \pre `mesh` is a consistently oriented manifold (closed, with borders, of any genus).
/// \throw BadInput naming the charts and features (chart_regions' rules, map_texture's per
///        chart, a feature given at different places in two charts);
///        TopologyError for a non-manifold mesh; InternalError if the map fails its certificate.
ChartsResult map_charts(const TriMesh& mesh, const std::vector<ChartInput>& charts, const MapOptions& options = {});

}  // namespace ctmap
