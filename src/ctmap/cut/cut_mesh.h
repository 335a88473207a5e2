#pragma once
/// \file cut_mesh.h
/// The result of the cut (paper §2.3, Table 1): the mesh refined so that every edge of the
/// feature triangulation is a chain of mesh edges, and the faces grouped into one patch per image
/// triangle. This is what the embedding (paper §2.4) consumes.
#include <array>
#include <vector>

#include "ctmap/cut/approximate_path.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// One patch: the faces mapped into one triangle of the feature triangulation.
struct Patch {
    Tri corners;  ///< feature indices, in the order of the image triangle (counter-clockwise)
    /// sides[k]: mesh vertex chain from the vertex of corners[k] to the vertex of corners[(k+1)%3],
    /// both ends included. The patch lies on the left of each side (the mesh's orientation).
    std::array<std::vector<int>, 3> sides;
};

/// The cut mesh.
struct CutMesh {
    /// Refined mesh: vertices [0, num_input_vertices) are the input's, same order and position;
    /// inserted vertices follow and lie on the input surface. Faces are new.
    TriMesh mesh;
    int num_input_vertices = 0;
    std::vector<int> feature_vertex;  ///< per feature, its vertex in `mesh`
    std::vector<int> face_patch;      ///< per face of `mesh`, its patch (= image triangle index)
    std::vector<Patch> patches;       ///< one per triangle of the feature triangulation, same index
    /// Per vertex of `mesh`: the input face it lies in (barycentric coordinates in `vertex_bary`),
    /// so UVs can be carried back to the input surface. Input vertices: any incident face.
    std::vector<int> vertex_face;
    std::vector<Vec3> vertex_bary;
    int steiner_vertices = 0;  ///< vertices added by the fallback (condition 4), not on paths
};

}  // namespace ctmap

#include <functional>
#include <string>

namespace ctmap {

/// Options of `cut_mesh`.
struct CutOptions {
    /// Steiner point spacing relative to the mean edge length of the input (paper §2.3: "given a
    /// constant length, each edge is inserted with several intermediate points").
    double spacing_factor = 0.34;
    /// A path's spacing is also at most this fraction of the 3D distance between its ends, down
    /// to 1/64 of the mesh's spacing (0: the mesh's spacing only). Features much closer together than the mesh's edges (dense
    /// point sets) otherwise get paths made of the few points the coarse spacing leaves, which
    /// hug each other and close sectors.
    double reach_spacing_factor = 0.25;
    /// Paths from CGAL's exact geodesics (`find_exact_path`) instead of the Steiner-graph search,
    /// for comparison; a geodesic that breaks the path rules (it may cross a path, pass through a
    /// blocked vertex or leave outside its sector) is replaced by the approximate search. Not
    /// used by a guided cut (a geodesic knows nothing of the guide).
    bool exact_geodesics = false;
    /// The coarse-to-fine search (see PathSearchOptions): vertex rings of the corridor (0: every
    /// path in the whole fine graph), and the distance between a path's ends, in spacings, from
    /// which it is used.
    int corridor_rings = PathSearchOptions{}.corridor_rings;
    double corridor_min_distance = PathSearchOptions{}.corridor_min_distance;
    /// Insertion order. `nearest` (the paper's): a spanning tree grown from the border by 3D
    /// distance (Prim), then the closing edges shortest first. `shortest_path`: the same two stages,
    /// but each step inserts the edge whose path, searched in the network as it stands, is the
    /// shortest (lazily: a path's length only grows as others are inserted, so a candidate searched
    /// since the last insertion that is still the shortest is taken): a path that would wind round
    /// others is put off until it is needed, or left to the closing stage. Not with exact geodesics.
    enum class Order { nearest, shortest_path };
    Order order = Order::nearest;
    /// How many times the fallback may refine around a path's ends before giving up.
    int max_refinements = 8;
    /// Straighten each inserted path inside every input face it crosses (straighten_path.h):
    /// bounds the growth of the mesh where paths run side by side.
    bool straighten = true;
    /// Paths short on the surface only (the paper), short in the guide map as well
    /// (guide_map.h), or automatic: on the surface in `order` first; when the work mesh outgrows
    /// `growth_limit` times (input faces + 20 per feature), again from scratch on the surface with
    /// the paths shortest first; past three times that limit, guided (shortest first). Dense
    /// layouts need about 20 faces per feature (10,034 points on nefertiti: 201,712 faces).
    /// Twisted layouts (image neighbours in other directions than on the surface) make paths
    /// inserted in the paper's order wind ever longer around the earlier ones; shortest first
    /// puts those off (three_peaks, 400 features, twist 8: 45,189 faces; twist 10: 87,743).
    enum class Guide { off, on, automatic };
    Guide guide = Guide::automatic;
    /// A guided move costs its surface length plus this times its guide length, the guide scaled
    /// to the surface's area.
    double guide_weight = 4;
    double growth_limit = 6;
    /// A guided cut runs on the input subdivided this many times (1-to-4 at edge midpoints: the
    /// same surface, subdivide.h) and the guide with it: on a coarse input the guide folds where
    /// the layout twists (a face too large for the shear across it), and its paths then grow the
    /// mesh further. three_peaks with 400 features twisted by 8, paper's order: 133,473 faces at
    /// 0, 91,074 at 1 and a map 180 times less distorted (BENCHMARKS.md, "Hard layouts").
    int guide_subdivisions = 1;
    /// Called as paths are inserted (for progress lines): `stage` is "paths", or, when the
    /// automatic cut gives a cut up and starts again, "paths (again, shortest first)" or "paths
    /// (again, guided)", so that a count that starts over comes under a name of its own.
    std::function<void(const std::string& stage, int done, int total)> progress;
};

/// Counts of the cut, for reports and benchmarks.
struct CutStats {
    int paths = 0;              ///< interior paths searched and inserted
    int fallback_fired = 0;     ///< paths that needed the refinement fallback
    int steiner_vertices = 0;   ///< vertices added by the fallback
    int inserted_vertices = 0;  ///< all vertices added (paths + fallback)
    double path_length = 0;     ///< total length of the interior paths
    int exact_paths = 0;        ///< paths inserted as exact geodesics (exact_geodesics on)
    int exact_rejected = 0;     ///< exact geodesics that broke the rules: approximate search used
    int corridor_paths = 0;     ///< paths found in the corridor of a coarse path
    int corridor_misses = 0;    ///< paths the coarse search or its corridor missed: whole graph searched
    int straightened_vertices = 0;  ///< path vertices removed by straightening
    int kept_runs = 0;              ///< runs straightening left as they were
    /// Where the added vertices lie: inside an input edge (a path crossing it: the growth no cut
    /// avoids), or inside an input face (Steiner vertices, and path vertices straightening kept).
    int vertices_on_input_edges = 0;
    int vertices_inside_faces = 0;
    /// The paths were searched with the guide map; inserted shortest first (CutOptions::Order);
    /// `guide_restart_faces`: the work mesh's faces when the paper's cut was given up (automatic
    /// mode: for the shortest-first one; 0: it was not); `shortest_path_restart_faces`: the same
    /// for the shortest-first cut on the surface, given up for the guided one.
    bool guided = false;
    bool shortest_path_first = false;
    int guide_restart_faces = 0;
    int shortest_path_restart_faces = 0;
    int guide_subdivisions = 0;  ///< times the input was subdivided for the guided cut
};

/// The Steiner point spacing the path search of `cut_mesh` uses on `mesh` (world units):
/// `options.spacing_factor` times the mean edge length. \pre `mesh` has faces.
double steiner_spacing(const TriMesh& mesh, const CutOptions& options = {});

/// The border features in the order the mesh border meets them (interior on the left), starting
/// anywhere. \pre `mesh` is a disc; feature_vertex holds distinct vertex ids.
std::vector<int> border_features(const TriMesh& mesh, const std::vector<int>& feature_vertex);

/// Cuts `mesh` into one patch per triangle of `ft` (paper §2.3, Table 1): border edges of the
/// triangulation follow the mesh border; interior edges become approximate shortest paths,
/// inserted border first, then a spanning tree of the remaining features (so that every region
/// stays a disc whose boundary holds all its features: closing an edge then cannot block a later
/// one), then the remaining edges shortest first. Each path respects DESIGN §2 conditions 1-3;
/// when none exists the mesh is refined around the path's ends (Steiner vertices) and the search
/// repeated (condition 4).
/// \pre `mesh` is a disc; `ft` was built from the features' image points with the border order
///      of `border_features`.
/// \throw InternalError if the cut fails on this (valid) input.
CutMesh cut_mesh(const TriMesh& mesh, const std::vector<int>& feature_vertex, const FeatureTriangulation& ft,
                 const CutOptions& options = {}, CutStats* stats = nullptr);

}  // namespace ctmap
