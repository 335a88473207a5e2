#pragma once
/// \file incremental_remap.h
/// The re-map of `ctmap serve` after one feature's image point moved (issue 15): the previous
/// optimised map, its feature moved by a bump deformation (refine/bump_move.h), optimised again
/// with the same energy (refine/isometric.h) and certified. Beyond the paper: its §2.4 relaxes a
/// fresh embedding; here the previous answer is the start, so a small move costs a few
/// iterations instead of the whole pipeline.
#include <optional>
#include <string>

#include "ctmap/map_texture.h"

namespace ctmap {

/// `previous` with given feature `feature` moved to UV `target`, optimised and certified; empty
/// (the caller maps in full) when the move cannot start from `previous`: options without the
/// optimiser, a move too large for the bump, a start that is not valid, or a certificate that
/// fails. `why` (if given) says which.
/// \pre `previous` came from map_texture with `options`; 0 <= feature < given features.
std::optional<MapResult> remap_moved_feature(const MapResult& previous, int feature, const Vec2& target,
                                             const MapOptions& options, std::string* why = nullptr);

}  // namespace ctmap
