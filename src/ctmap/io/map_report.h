#pragma once
/// \file map_report.h
/// The report `ctmap map --report` writes (issue 4): counts, stage times like the paper's Table 2,
/// the certificate and the distortion before and after the refinement.
#include <nlohmann/json.hpp>
#include <string>

#include "ctmap/map_texture.h"

namespace ctmap {

/// The distortion measures as JSON (a non-finite measure as null), as every report writes them.
nlohmann::json distortion_json(const Distortion& d);

/// The inputs a report names.
struct MapReportInputs {
    std::string mesh, features, image;
    int image_width = 0, image_height = 0;
    int input_vertices = 0, input_faces = 0;
};

/// The report of one map. Keys: `inputs`, `counts` {features, point_features, triangles (image
/// triangles = patches), paths, input_vertices, input_faces, vertices, faces, inserted_vertices,
/// steiner_vertices, flat_edges_split, fallback_fired}, `timings_ms` {read, triangulate, paths,
/// embed, refine, optimise, certify, total}, `certificate` (certificate_to_json, with the
/// distortion of the written map), `distortion_before_refine` (the bare embedding),
/// `distortion_after_relax` (after the paper's relaxation), `relax` {sweeps, moves, converged,
/// ...}, `optimiser` (null with --refine paper) {iterations, energy (the symmetric Dirichlet
/// energy on entry and after each iteration), converged, stop, halvings, exact_rejections,
/// border_rejections, free_vertices, sliding_vertices}.
nlohmann::json map_report(const MapResult& result, const MapReportInputs& inputs);

}  // namespace ctmap
