#pragma once
/// \file edit_session.h
/// The state behind `ctmap serve` (issue 15, the paper's interactive adjustment of features, §1 and
/// §2.2): one mesh, one image, the current features and the last certified map. Every change of
/// the features maps again (the whole pipeline: map_texture, certified); a change that makes the
/// layout invalid is refused with the message `ctmap map` gives, and the session keeps its last
/// valid features and map. Not thread-safe: the server serialises the calls.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "ctmap/io/features.h"
#include "ctmap/map_texture.h"

namespace ctmap {

/// What an editing session maps with (the options of `ctmap map`).
struct EditSessionOptions {
    MapOptions map;
    /// A move starts from the last map (edit/incremental_remap.h) when it can; off: every change
    /// runs the whole pipeline.
    bool incremental = true;
};

class EditSession {
public:
    /// \pre `mesh` passed `require_disc` (the server reads and checks it like `ctmap map`);
    ///      `width`, `height` > 0 (the image's size). `features_path` names the features in
    ///      messages and is where `save` writes (empty: nothing to save to).
    /// \throw BadInput if `initial` (when given) is not a valid layout, as set_features.
    EditSession(TriMesh mesh, std::string mesh_path, std::string image_path, int width, int height,
                std::string features_path, std::optional<FeatureSet> initial, EditSessionOptions options = {});

    /// The session as JSON: {"mesh": {path, vertices (flat xyz), faces (flat)}, "image": {path,
    /// width, height}, "features": the features document (pixels), "map": as `answer` or null}.
    nlohmann::json state() const;

    /// Replaces every feature by those of a features document (DESIGN §4 text; its `image` and
    /// `image_size` are ignored: the session's image is used) and maps.
    /// \return `answer()` of the new map. \throw BadInput (the message of `ctmap map`, naming the
    ///         features file) if the document or the layout is invalid; the session is unchanged.
    nlohmann::json set_features(const std::string& document);

    /// Moves feature `name`'s image point to `image` (pixels) and maps: from the last map when it
    /// can (EditSessionOptions::incremental), else in full; the layout is checked as `ctmap map`
    /// checks it either way.
    /// \throw BadInput for an unknown name, a point outside the image or an invalid layout; the
    ///        session is unchanged.
    nlohmann::json move(const std::string& name, const Vec2& image);

    /// The last map: its report (as `ctmap map --report` writes it) with "uv" (per vertex of the
    /// cut mesh, flat u v), "vertices" (flat xyz), "faces" (flat) and "update" ("full" or
    /// "incremental"; with "full_because" when a move could not start from the last map) added;
    /// null before any map. `with_mesh` false leaves out "vertices" and "faces" (a move's answer
    /// from the last map: its cut mesh is the one of the answer with the same "mesh_revision").
    nlohmann::json answer(bool with_mesh = true) const;

    /// The current features as a features document (DESIGN §4, pixels).
    std::string features_document() const;

    /// Writes the current features to the features path (atomically). \throw BadInput if the
    /// session has no features path; InternalError if it cannot be written.
    void save() const;

    const std::optional<MapResult>& map() const { return map_; }
    const FeatureSet& features() const { return features_; }
    const std::string& image_path() const { return image_path_; }
    const TriMesh& mesh() const { return mesh_; }

private:
    /// Checks and maps `fs` (pixels); on success makes it the session's features and map.
    /// The features file as messages name it ("features" when the session has none).
    std::string file_name() const;
    /// `fallback`: why a move is mapped in full (the answer's "full_because"), kept on success only.
    void apply(FeatureSet fs, const std::string& fallback = "");

    TriMesh mesh_;
    std::string mesh_path_, image_path_, features_path_;
    int width_, height_;
    EditSessionOptions options_;
    FeatureSet features_;
    std::optional<MapResult> map_;
    /// The layout check of map_'s features with the mesh's share done (moves change only image points).
    std::optional<FeatureLayoutChecker> checker_;
    std::string last_update_;    ///< how the last map was made: "full" or "incremental"
    std::string last_fallback_;  ///< why the last move was mapped in full (empty: it was not a move)
    long mesh_revision_ = 0;     ///< counts the full maps: a new cut mesh each
};

}  // namespace ctmap
