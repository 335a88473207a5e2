#pragma once
/// \file chart_features.h
/// Features files with charts (issue 13, DESIGN §4; paper §3): several images on one mesh, each
/// chart bounded by its border features, charts joined along seams.
#include <string>
#include <vector>

#include "ctmap/io/features.h"

namespace ctmap {

/// One chart of a features file: its image and its features' image points.
struct ChartFeatures {
    std::string name;
    /// The chart's features with their image points in this chart. Every feature has its mesh
    /// place (`vertex` or `point`), filled in from another chart where this chart leaves it out.
    /// `features.path` is the file; `features.image`, `image_size` and `units` are the chart's.
    FeatureSet features;
    /// The chart's border features, in order around its image polygon (either direction). Empty
    /// only for a file's one chart: it is bounded by the mesh border, as a file without charts.
    std::vector<std::string> border;
};

/// The OBJ/glTF material of chart `name`: "chart_<name>" (the faces in no chart have "rest").
inline std::string chart_material_name(const std::string& name) { return "chart_" + name; }

/// A parsed features file with `charts`.
struct ChartFile {
    std::string path;
    std::vector<ChartFeatures> charts;
};

/// True if the JSON text is an object with a `charts` member (cheap: for choosing the reader).
/// \throw BadInput as parse_features for text that is not JSON.
bool has_charts(const std::string& text, const std::string& path);

/// Reads and checks a features file with charts: each chart as a features file of its own
/// (read_features' rules), chart names unique, of letters, digits, '_' and '-' (they name the
/// OBJ's materials), a feature's mesh place given at least once and the
/// same wherever repeated, border names known to their chart, unique, at least 3, and present in
/// every chart but a lone one.
/// \throw BadInput naming the file, the charts and the features of every violation.
ChartFile read_chart_features(const std::string& path);

/// Same, from text (`path` names it and resolves image paths).
ChartFile parse_chart_features(const std::string& text, const std::string& path);

/// Every chart's image points in pixels (resolve_feature_image per chart: its `image`, else its
/// `image_size`). \return per chart, its image path (empty when only a size was given);
/// `sizes` receives [W, H] per chart. \throw BadInput naming the file and the chart.
std::vector<std::string> resolve_chart_images(ChartFile& cf, std::vector<std::array<int, 2>>& sizes);

}  // namespace ctmap
