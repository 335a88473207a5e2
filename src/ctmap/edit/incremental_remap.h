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

/// How far a move reaches into the map.
struct RemapOptions {
    /// Local (the default): the bump's radius is at most `radius` times the diagonal of the map's
    /// UV bounding box, and only the vertices within
    /// `region` times that radius of the move's path are optimised, the rest held where they
    /// are: a drag's answer costs a small system. Off: the bump reaches to the nearest other
    /// feature and the whole map is optimised (slower, the energy's minimum over the whole map).
    bool local = true;
    /// Only moves up to this fraction of the map's UV diagonal are local (a drag's steps); a
    /// longer jump shifts the distortion too far for a region of that size and optimises the
    /// whole map (measured: a 25-px jump on lion-head ended 16% above a full map when local).
    double local_reach = 0.02;
    double radius = 0.08;
    double region = 1.5;
    /// The radius shrinks until about this many vertices lie in the optimised region (not below
    /// what a bump of the move's length needs).
    int region_vertices = 600;
};

/// `previous` with given feature `feature` moved to UV `target`, optimised and certified; empty
/// (the caller maps in full) when the move cannot start from `previous`: options without the
/// optimiser, a move too large for the bump, a start that is not valid, or a certificate that
/// fails. `why` (if given) says which.
/// \pre `previous` came from map_texture with `options`; 0 <= feature < given features.
/// \throw BadInput for `remap` out of range (region_vertices or radius not positive, region < 1,
///        local_reach negative). The local mode's optimiser stops by the tolerance relative to the
///        whole map's energy (the held faces' share included), as a whole-map run would.
std::optional<MapResult> remap_moved_feature(const MapResult& previous, int feature, const Vec2& target,
                                             const MapOptions& options, std::string* why = nullptr,
                                             const RemapOptions& remap = {});

}  // namespace ctmap
