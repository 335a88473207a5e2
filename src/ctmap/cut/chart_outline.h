#pragma once
/// \file chart_outline.h
/// One chart as the seams need it (paper §3): its features' vertices on the mesh, the border
/// ones in order round its image polygon.
#include <string>
#include <vector>

namespace ctmap {

/// One chart as the seams need it: its features' vertices (of the mesh given to chart_regions).
struct ChartOutline {
    std::string name;
    std::vector<int> border;                ///< border feature vertices, in order around the image polygon
    std::vector<std::string> border_names;  ///< their names, for messages
    std::vector<int> interior;              ///< the chart's other feature vertices
    std::vector<std::string> interior_names;
    bool image_ccw = true;  ///< the border's image polygon runs counter-clockwise (UV, v up)
};

}  // namespace ctmap
