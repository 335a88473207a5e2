#include "ctmap/edit/edit_session.h"

#include <filesystem>
#include <utility>

#include "ctmap/edit/incremental_remap.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/map_report.h"

namespace ctmap {

EditSession::EditSession(TriMesh mesh, std::string mesh_path, std::string image_path, int width, int height,
                         std::string features_path, std::optional<FeatureSet> initial, EditSessionOptions options)
    : mesh_(std::move(mesh)),
      mesh_path_(std::move(mesh_path)),
      image_path_(std::move(image_path)),
      features_path_(std::move(features_path)),
      width_(width),
      height_(height),
      options_(std::move(options)) {
    if (width_ <= 0 || height_ <= 0) throw BadInput(image_path_, "the image has no pixels");
    features_.path = features_path_;
    features_.image = image_path_;
    features_.image_size = std::array<int, 2>{width_, height_};
    if (initial) {
        initial->image = image_path_;
        initial->image_size = std::array<int, 2>{width_, height_};
        apply(std::move(*initial));
    }
}

std::string EditSession::file_name() const { return features_path_.empty() ? "features" : features_path_; }

void EditSession::apply(FeatureSet fs, const std::string& fallback) {
    fs.path = features_path_;
    fs.image = image_path_;
    fs.image_size = std::array<int, 2>{width_, height_};
    // What `ctmap map` checks after reading, in its order, with its messages.
    resolve_units(fs, width_, height_);
    check_features_on_mesh(fs, mesh_, mesh_path_, options_.map.snap);
    MapResult r = naming_file(file_name(),
                              [&] { return map_texture(mesh_, map_features(fs, width_, height_), options_.map); });
    std::optional<FeatureLayoutChecker> checker;
    if (options_.incremental)
        checker = naming_file(file_name(), [&] {
            return FeatureLayoutChecker(mesh_, map_features(fs, width_, height_), options_.map.snap,
                                        options_.map.auto_border);
        });
    features_ = std::move(fs);
    map_ = std::move(r);
    checker_ = std::move(checker);
    last_update_ = "full";
    last_fallback_ = fallback;  // only now: a refused change leaves the session as it was
    ++mesh_revision_;
}

nlohmann::json EditSession::set_features(const std::string& document) {
    FeatureSet fs = parse_features(document, file_name());
    apply(std::move(fs));
    return answer();
}

nlohmann::json EditSession::move(const std::string& name, const Vec2& image) {
    FeatureSet fs = features_;
    bool found = false;
    for (Feature& f : fs.features)
        if (f.name == name) {
            f.image = image;
            found = true;
        }
    if (!found) throw BadInput(file_name(), "no feature \"" + name + "\"");
    if (!image.allFinite())
        throw BadInput(file_name(),
                       "feature \"" + name + "\": its image point is not finite");
    fs.units = "pixels";
    const std::string file = file_name();
    std::string fallback;
    if (map_ && checker_) {
        // What `ctmap map` would refuse is refused with its message; a valid layout then starts
        // from the last map (edit/incremental_remap.h), or is mapped in full if it cannot.
        FeatureSet checked = fs;
        resolve_units(checked, width_, height_);
        naming_file(file, [&] { return checker_->check(map_features(checked, width_, height_)); });
        int index = 0;
        while (checked.features[index].name != name) ++index;
        std::optional<MapResult> r = remap_moved_feature(*map_, index, image_to_uv(checked.features[index].image, width_, height_),
                                                         options_.map, &fallback);
        if (r) {
            features_ = std::move(checked);
            map_ = std::move(r);
            last_update_ = "incremental";
            last_fallback_.clear();
            return answer(false);  // the cut mesh is unchanged
        }
    }
    apply(std::move(fs), fallback);
    return answer();
}

namespace {

template <class T>
nlohmann::json flat(const std::vector<T>& items) {
    nlohmann::json out = nlohmann::json::array();
    for (const T& p : items)
        for (const auto x : p) out.push_back(x);
    return out;
}

}  // namespace

nlohmann::json EditSession::answer(bool with_mesh) const {
    if (!map_) return nullptr;
    MapReportInputs in{mesh_path_, features_path_, image_path_, width_, height_, mesh_.num_vertices(),
                       mesh_.num_faces()};
    nlohmann::json j = map_report(*map_, in);
    j["uv"] = flat(map_->uv);
    if (with_mesh) {
        j["vertices"] = flat(map_->cut.mesh.positions);
        j["faces"] = flat(map_->cut.mesh.faces);
    }
    j["mesh_revision"] = mesh_revision_;  // which cut mesh the UVs belong to (an answer without it reuses it)
    j["update"] = last_update_;  // "full": the whole pipeline; "incremental": from the previous map
    if (last_update_ == "full" && !last_fallback_.empty()) j["full_because"] = last_fallback_;
    return j;
}

nlohmann::json EditSession::state() const {
    nlohmann::json j;
    j["mesh"] = {{"path", mesh_path_}, {"vertices", flat(mesh_.positions)}, {"faces", flat(mesh_.faces)}};
    j["image"] = {{"path", image_path_}, {"width", width_}, {"height", height_}};
    j["features"] = nlohmann::json::parse(features_document());
    j["map"] = answer();
    return j;
}

std::string EditSession::features_document() const {
    // The image as the saved file will resolve it: relative to the features file's folder.
    FeatureSet fs = features_;
    if (!features_path_.empty() && !fs.image.empty()) {
        namespace fsys = std::filesystem;
        std::error_code ec;
        const fsys::path folder = fsys::absolute(fsys::path(features_path_), ec).parent_path();
        const fsys::path rel = fsys::relative(fsys::absolute(fs.image, ec), folder, ec);
        if (!ec && !rel.empty()) fs.image = rel.string();
    }
    return features_to_json(fs);
}

void EditSession::save() const {
    if (features_path_.empty()) throw BadInput("features", "no features file to save to: give one to `ctmap serve`");
    write_text_file(features_path_, features_document());
}

}  // namespace ctmap
