#pragma once
/// \file map_texture.h
/// The whole constrained texture mapping pipeline (paper §2, steps 2-4): feature triangulation
/// in the image, the cut into matching patches, the mean value embedding of each patch, the
/// relaxation, and the certificate. `ctmap map`, `ctmap demo`, the tests and the benchmarks all
/// call this one function, so what they measure is what users run.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ctmap/certify/certificate.h"
#include "ctmap/cut/cut_mesh.h"
#include "ctmap/domain/auto_border.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/embed/mean_value_embedding.h"
#include "ctmap/io/features.h"
#include "ctmap/mesh.h"
#include "ctmap/refine/isometric.h"
#include "ctmap/refine/relax.h"

namespace ctmap {

/// What the refinement does after the relaxation (`--refine`).
enum class RefineMode {
    paper,      ///< the paper's relaxation only (§2.4)
    isometric,  ///< the relaxation, then the distortion optimiser (refine/isometric.h)
};

/// Options of `map_texture`.
struct MapOptions {
    CutOptions cut;
    EmbedOptions embed;
    RelaxOptions relax;
    bool refine = true;  ///< run the relaxation (paper §2.4); off gives the bare embedding
    /// `--border auto` (true): place border features where the given ones cannot make a border
    /// (domain/auto_border.h); `--border given` (false): the paper's rules, refused otherwise.
    bool auto_border = true;
    RefineMode refine_mode = RefineMode::isometric;
    /// The optimiser's options (with RefineMode::isometric). Its border mode also decides the
    /// relaxation's: with a fixed border the relaxation leaves the border vertices on their sides.
    IsometricOptions isometric;
    /// How far a point feature may be moved onto a vertex near it, in the mesh's units (< 0:
    /// kDefaultSnapFraction of the bounding-box diagonal); `--snap`.
    double snap = -1;
    /// Called when a stage starts ("triangulate", "paths", "embed", "refine", "optimise",
    /// "certify") and, for the paths and the optimiser's iterations, as they are done (done of
    /// total); for progress lines.
    std::function<void(const std::string& stage, int done, int total)> progress;
};

/// Wall-clock milliseconds per stage, like the paper's Table 2 (`read` is filled by callers that
/// read files; `total` is the sum of the stages run here plus `read`).
struct MapTimings {
    double read = 0, triangulate = 0, paths = 0, embed = 0, refine = 0, optimise = 0, certify = 0, total = 0;
};

/// One feature for `map_texture`: a vertex of the input mesh, or a 3D point on its surface
/// (vertex -1), and its UV (DESIGN §3: u = x / W, v = 1 - y / H).
struct MapFeature {
    std::string name;
    int vertex = -1;
    Vec3 point = Vec3::Zero();
    Vec2 uv{0, 0};
};

/// The result: a certified map.
struct MapResult {
    /// The cut mesh: its vertices [0, |V|) are the input's in order (DESIGN §3); point features,
    /// path and Steiner vertices follow. `cut.feature_vertex[i]` is feature i's vertex.
    /// `cut.feature_vertex` lists the given features only (the added border features are in
    /// `auto_border`); `triangulation` and the patches' corners index the given features, then
    /// the added ones: feature `given + j` is `auto_border.vertex[j]` (use `feature_vertex_of`).
    CutMesh cut;
    std::vector<Vec2> uv;             ///< one UV per vertex of cut.mesh (the written map)
    std::vector<Vec2> feature_uv;     ///< per given feature, its UV constraint
    /// The border features ctmap placed (`MapOptions::auto_border`): their vertices (of cut.mesh)
    /// and the UVs they started at; none when the given features make a border.
    AutoBorder auto_border;
    /// Whether the added border features kept their UVs (the paper's relaxation, a fixed
    /// border) or only started the border (the optimiser with a free border moves them).
    bool auto_border_fixed = true;
    FeatureTriangulation triangulation;
    CutStats cut_stats;
    FlatEdgeStats flat_edges;
    RelaxStats relax_stats;
    IsometricStats isometric_stats;   ///< empty unless RefineMode::isometric; its `scale` is for `cut.mesh` as returned
    Distortion before_refine;         ///< distortion of the bare embedding
    Distortion after_relax;           ///< distortion after the paper's relaxation (before the optimiser)
    Certificate certificate;          ///< of the written map (valid, or map_texture throws)
    MapTimings timings_ms;
    /// Per face of cut.mesh, the face of the input mesh it lies in (input_faces.h).
    std::vector<int> input_face;
    int point_features = 0;           ///< features given as 3D points (inserted as vertices)
    double point_features_moved = 0;  ///< the largest distance a point feature moved onto the mesh

    /// The vertex of feature `i` as the triangulation and the patches count them (given
    /// features first, then the added border features).
    int feature_vertex_of(int i) const {
        const int given = int(cut.feature_vertex.size());
        return i < given ? cut.feature_vertex[i] : auto_border.vertex.at(i - given);
    }

    /// The map as a textured mesh with per-vertex UVs (one chart), ready for write_obj/write_glb.
    /// Faces carry their patch (`TexturedMesh::patch`), so the OBJ shows the cut as groups.
    TexturedMesh textured() const {
        TexturedMesh t = TexturedMesh::with_vertex_uvs(cut.mesh, uv);
        t.patch = cut.face_patch;
        t.input_face = input_face;
        return t;
    }
};

/// Maps `mesh` so that every feature lands exactly on its UV (paper §2.2-2.4). Point features are
/// first inserted as vertices (the face or edge they lie on is split; a point on a vertex uses the
/// vertex). The map is certified (exact predicates) before it is returned.
/// \pre `mesh` is a manifold disc (io's `require_disc`); features are distinct, finite, with UVs
///      that `triangulate_features` accepts.
/// \throw BadInput naming the features for an infeasible feature layout (fewer than 3 border
///        features, a border polygon that is not simple, ...), naming no file (a caller that read
///        the features from a file adds it: `naming_file` in errors.h); InternalError if the cut fails or the map does not pass its certificate (no
///        invalid map is ever returned).
MapResult map_texture(const TriMesh& mesh, const std::vector<MapFeature>& features, const MapOptions& options = {});

/// A map as arrays (issue 16), for callers that hold meshes as Eigen matrices (libigl's V, F).
struct MapArrays {
    Eigen::MatrixXd V;           ///< n' x 3: the cut mesh (the input's vertices first, in order)
    Eigen::MatrixXi F;           ///< m' x 3
    Eigen::MatrixXd UV;          ///< 3m' x 2: per face corner, corner k of face f in row 3f + k (OBJ's convention, v up)
    Eigen::VectorXi chart;       ///< m': the chart of each face (0: one chart)
    Eigen::VectorXi feature_vertex;  ///< per given feature, its row of V
    MapResult result;            ///< everything else: certificate, distortion, timings, the cut
};

/// `map_texture` on matrices: `V` n x 3 positions, `F` m x 3 vertex indices (0-based).
/// \pre none beyond the types: sizes, finite positions and indices in range are checked.
/// \throw BadInput for a malformed V or F and as map_texture.
MapArrays map_texture(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<MapFeature>& features,
                      const MapOptions& options = {});

/// What `check_feature_layout` found: the triangulation `map_texture` would cut along (over the
/// given features, then the added border features) and the border features it would add.
struct FeatureLayout {
    FeatureTriangulation triangulation;
    AutoBorder auto_border;
};

/// Every check `map_texture` makes before the cut (paper §2.2): vertex indices, point features on
/// distinct vertices, at least 3 border features in the mesh border's cyclic order (or, with
/// `auto_border`, the border features it would place), a simple border polygon that holds every
/// interior feature, distinct feature points. `ctmap validate` runs it, so it gives the verdict
/// and the message `ctmap map` would.
/// \pre as map_texture. \throw BadInput as map_texture.
FeatureLayout check_feature_layout(const TriMesh& mesh, const std::vector<MapFeature>& features,
                                   double snap = -1, bool auto_border = true);

/// `check_feature_layout` for a feature set whose image points change while the features stay at
/// their mesh vertices and points (`ctmap serve`'s drags): the mesh's share of the checks (mesh
/// topology, vertex indices, points put on the mesh) is done once, in the constructor.
class FeatureLayoutChecker {
public:
    /// \pre as check_feature_layout. \throw BadInput as check_feature_layout, for the mesh's share.
    FeatureLayoutChecker(const TriMesh& mesh, const std::vector<MapFeature>& features, double snap = -1,
                         bool auto_border = true);
    /// check_feature_layout(mesh, features, snap, auto_border), the same verdict and message.
    /// \pre `features` are the constructor's with only their UVs changed (else BadInput).
    FeatureLayout check(const std::vector<MapFeature>& features) const;

private:
    struct State;
    std::shared_ptr<const State> state_;
    bool auto_border_;
    std::vector<std::string> names_;
    std::vector<int> vertex_;
    std::vector<Vec3> point_;
};

/// Puts the point features of `features` on `mesh` as vertices, as `map_texture` does (a point
/// within `snap` of a vertex uses it, else the face or edge it lies on is split); the input's
/// vertices keep their indices and coordinates, inserted ones follow. `ctmap morph` uses it to
/// know which pairs lie on the border before mapping.
/// \pre every vertex index in range; points finite. \return per feature, its vertex.
std::vector<int> place_point_features(TriMesh& mesh, const std::vector<MapFeature>& features, double snap = -1);

/// The features of a features file for `map_texture`. \pre `resolve_units(fs, width, height)`
/// was called (image points in pixels).
std::vector<MapFeature> map_features(const FeatureSet& fs, int width, int height);

}  // namespace ctmap
