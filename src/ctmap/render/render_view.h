/// \file render_view.h
/// Helpers the renderer's two halves share (render_view.cpp: names, colours, camera;
/// render_map.cpp: drawing). Internal to render/.
#pragma once

#include <array>
#include <cstdint>

#include "ctmap/render/render_map.h"

namespace ctmap::render_detail {

/// An RGB colour from hue, saturation and value, each in [0, 1] (hue wraps).
std::array<std::uint8_t, 3> hsv(double h, double s, double v);

/// Bounding box of the map's UVs (all of them, or those of the triangulation's points for
/// `RenderMode::triangulation`). \pre the scene passed the renderer's input checks.
Eigen::AlignedBox2d uv_box(const RenderScene& scene, RenderMode mode);

}  // namespace ctmap::render_detail
