#include "ctmap/io/features.h"

#include "ctmap/io/image.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/json_document.h"
#include "ctmap/io/printable.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

using json = nlohmann::json;

class Problems {
public:
    void add(std::string p) { list_.push_back(std::move(p)); }
    bool empty() const { return list_.empty(); }
    void throw_if_any(const std::string& file, const std::string& intro) const {
        if (list_.empty()) return;
        std::string msg = intro;
        for (const auto& p : list_) msg += "\n  - " + p;
        throw BadInput(file, msg);
    }

private:
    std::vector<std::string> list_;
};

std::string short_number(double x) {
    std::ostringstream os;
    os << std::setprecision(3) << x;
    return os.str();
}

std::string fmt(const Vec2& p) {
    std::ostringstream os;
    os << "(" << p.x() << ", " << p.y() << ")";
    return os.str();
}

}  // namespace

FeatureSet read_features(const std::string& path) {
    check_input_file(path, "features file");
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_features(ss.str(), path);
}

FeatureSet parse_features(const std::string& text, const std::string& path) {
    json doc = parse_json_document(text, path, "features file");
    if (!doc.is_object()) throw BadInput(path, "the features file must hold a JSON object with a \"features\" array");
    if (doc.contains("charts"))
        throw BadInput(path, "the file has \"charts\" (several images, issue 13): ctmap map reads it; this reader "
                             "takes one chart (a \"features\" array)");

    FeatureSet out;
    out.path = path;
    Problems problems;

    if (doc.contains("units")) {
        if (!doc["units"].is_string() || (doc["units"] != "pixels" && doc["units"] != "uv"))
            problems.add("wrong units " + printable(doc["units"].dump()) + ": use \"pixels\" or \"uv\"");
        else
            out.units = doc["units"].get<std::string>();
    }
    if (doc.contains("image")) {
        if (!doc["image"].is_string() || doc["image"].get<std::string>().empty())
            problems.add("\"image\" must be a non-empty file name (relative to the features file)");
        else {
            std::filesystem::path p(doc["image"].get<std::string>());
            if (p.is_relative()) p = std::filesystem::path(path).parent_path() / p;
            out.image = p.lexically_normal().string();
        }
    }
    if (doc.contains("image_size")) {
        const json& s = doc["image_size"];
        if (!s.is_array() || s.size() != 2 || !s[0].is_number_integer() || !s[1].is_number_integer() ||
            s[0].get<long long>() <= 0 || s[1].get<long long>() <= 0 || s[0].get<long long>() > 1000000 ||
            s[1].get<long long>() > 1000000)
            problems.add("\"image_size\" must be [W, H] with positive integer width and height");
        else
            out.image_size = std::array<int, 2>{s[0].get<int>(), s[1].get<int>()};
    }

    if (!doc.contains("features")) problems.add("missing field \"features\" (an array of features)");
    else if (!doc["features"].is_array()) problems.add("\"features\" must be an array");
    else if (doc["features"].empty()) problems.add("\"features\" is empty: at least one feature is needed");

    if (doc.contains("features") && doc["features"].is_array()) {
        int index = 0;
        for (const json& f : doc["features"]) {
            const std::string label = "feature #" + std::to_string(index++);
            if (!f.is_object()) {
                problems.add(label + " is not an object");
                continue;
            }
            Feature feat;
            if (!f.contains("name")) problems.add(label + ": missing field \"name\"");
            else if (!f["name"].is_string() || f["name"].get<std::string>().empty())
                problems.add(label + ": \"name\" must be a non-empty string");
            else
                feat.name = f["name"].get<std::string>();
            const std::string who = feat.name.empty() ? label : "feature " + quoted_name(feat.name);

            const bool has_vertex = f.contains("vertex"), has_point = f.contains("point");
            if (has_vertex == has_point)
                problems.add(who + ": give exactly one of \"vertex\" (a mesh vertex index) or \"point\" (a 3D point)");
            else if (has_vertex) {
                const json& v = f["vertex"];
                if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > 2000000000LL)
                    problems.add(who + ": \"vertex\" must be a non-negative integer index, got " + printable(v.dump()));
                else
                    feat.vertex = v.get<int>();
            } else {
                double p[3];
                if (!read_number_array(f["point"], 3, p)) problems.add(who + ": \"point\" must be [x, y, z]");
                else if (!all_finite(p, 3)) problems.add(who + ": \"point\" has a non-finite coordinate (NaN or infinity)");
                else feat.point = Vec3(p[0], p[1], p[2]);
            }

            double q[2];
            if (!f.contains("image")) problems.add(who + ": missing field \"image\" ([x, y] in " + out.units + ")");
            else if (!read_number_array(f["image"], 2, q)) problems.add(who + ": \"image\" must be [x, y]");
            else if (!all_finite(q, 2)) problems.add(who + ": \"image\" has a non-finite coordinate (NaN or infinity)");
            else feat.image = Vec2(q[0], q[1]);
            out.features.push_back(std::move(feat));
        }
    }
    problems.throw_if_any(path, "the features file is invalid:");

    // Uniqueness rules (DESIGN §4), each naming every feature involved.
    std::map<std::string, int> names;
    std::map<int, std::string> vertices;
    std::map<std::pair<double, double>, std::string> points;
    std::map<std::array<double, 3>, std::string> surface_points;
    for (const Feature& f : out.features) {
        if (++names[f.name] == 2) problems.add("the name " + quoted_name(f.name) + " is used by more than one feature");
        if (f.vertex >= 0) {
            auto [it, fresh] = vertices.emplace(f.vertex, f.name);
            if (!fresh)
                problems.add("features " + quoted_name(it->second) + " and " + quoted_name(f.name) + " both use vertex " +
                             std::to_string(f.vertex));
        } else if (f.point) {
            auto [it, fresh] = surface_points.emplace(std::array<double, 3>{f.point->x(), f.point->y(), f.point->z()}, f.name);
            if (!fresh)
                problems.add("features " + quoted_name(it->second) + " and " + quoted_name(f.name) + " are the same 3D point");
        }
        auto [it, fresh] = points.emplace(std::make_pair(f.image.x(), f.image.y()), f.name);
        if (!fresh)
            problems.add("features " + quoted_name(it->second) + " and " + quoted_name(f.name) + " have the same image point " +
                         fmt(f.image));
    }
    if (out.units == "uv")
        for (const Feature& f : out.features)
            if (f.image.x() < 0 || f.image.x() > 1 || f.image.y() < 0 || f.image.y() > 1)
                problems.add("feature " + quoted_name(f.name) + ": UV " + fmt(f.image) + " is outside [0, 1] x [0, 1]");
    problems.throw_if_any(path, "the features file is invalid:");
    return out;
}

void resolve_units(FeatureSet& fs, int width, int height) {
    Problems problems;
    if (fs.units == "uv") {
        for (Feature& f : fs.features) f.image = Vec2(f.image.x() * width, (1.0 - f.image.y()) * height);
        fs.units = "pixels";
    }
    for (const Feature& f : fs.features)
        if (!(f.image.x() >= 0 && f.image.x() <= width && f.image.y() >= 0 && f.image.y() <= height))
            problems.add("feature " + quoted_name(f.name) + ": image point " + fmt(f.image) + " is outside the " +
                         std::to_string(width) + " x " + std::to_string(height) + " image");
    problems.throw_if_any(fs.path, "features outside the image:");
}

double snap_tolerance(const TriMesh& mesh, double max_distance) {
    if (max_distance >= 0) return max_distance;
    Eigen::AlignedBox3d box;
    for (const Vec3& p : mesh.positions) box.extend(p);
    return kDefaultSnapFraction * box.diagonal().norm();
}

double check_features_on_mesh(const FeatureSet& fs, const TriMesh& mesh, const std::string& mesh_file,
                              double max_distance) {
    using K = CGAL::Exact_predicates_inexact_constructions_kernel;
    Problems problems;
    const double tol = snap_tolerance(mesh, max_distance);
    double moved = 0;
    for (const Feature& f : fs.features) {
        if (f.vertex >= mesh.num_vertices())
            problems.add("feature " + quoted_name(f.name) + " uses vertex " + std::to_string(f.vertex) + ", but " +
                         mesh_file + " has only " + std::to_string(mesh.num_vertices()) + " vertices");
        if (!f.point) continue;
        const K::Point_3 q(f.point->x(), f.point->y(), f.point->z());
        double best = std::numeric_limits<double>::infinity();
        for (const Tri& t : mesh.faces) {
            auto P = [&](int i) { return K::Point_3(mesh.positions[i].x(), mesh.positions[i].y(), mesh.positions[i].z()); };
            const K::Triangle_3 tri(P(t[0]), P(t[1]), P(t[2]));
            if (tri.is_degenerate()) continue;
            best = std::min(best, CGAL::to_double(CGAL::squared_distance(q, tri)));
        }
        if (!(std::sqrt(best) <= tol))
            problems.add("feature " + quoted_name(f.name) + ": its 3D point is " + short_number(std::sqrt(best)) +
                         " away from the surface of " + mesh_file + " (at most " + short_number(tol) +
                         " is accepted; --snap DIST sets the distance)");
        else
            moved = std::max(moved, std::sqrt(best));
    }
    problems.throw_if_any(fs.path, "the features do not match the mesh:");
    return moved;
}

std::vector<int> feature_vertices_on_map(const FeatureSet& fs, const TriMesh& mesh, const std::string& map_file,
                                         double max_distance) {
    const double tolerance = snap_tolerance(mesh, max_distance);
    std::vector<int> out;
    for (const Feature& f : fs.features) {
        int v = f.vertex;
        if (v < 0) {  // a 3D point: `ctmap map` put it on a vertex near it, or inserted one at it
            double best = std::numeric_limits<double>::infinity();
            for (int u = 0; u < mesh.num_vertices(); ++u)
                if (const double d = (mesh.positions[u] - *f.point).norm(); d < best) best = d, v = u;
            if (!(best <= tolerance))
                throw BadInput(fs.path, "feature " + quoted_name(f.name) + " is a 3D point with no vertex of " + map_file +
                                            " within " + short_number(tolerance) +
                                            " of it: was this map made from these features?");
        }
        out.push_back(v);
    }
    return out;
}

std::string features_to_json(const FeatureSet& fs) {
    nlohmann::ordered_json j;
    if (!fs.image.empty()) j["image"] = fs.image;
    if (fs.image_size) j["image_size"] = {(*fs.image_size)[0], (*fs.image_size)[1]};
    j["units"] = fs.units;
    j["features"] = nlohmann::ordered_json::array();
    for (const Feature& f : fs.features) {
        nlohmann::ordered_json e;
        e["name"] = f.name;
        if (f.vertex >= 0) e["vertex"] = f.vertex;
        else if (f.point) e["point"] = {f.point->x(), f.point->y(), f.point->z()};
        e["image"] = {f.image.x(), f.image.y()};
        j["features"].push_back(e);
    }
    return j.dump(2);
}

std::string resolve_feature_image(FeatureSet& fs, const std::string& image_arg, int& w, int& h) {
    const std::string image = !image_arg.empty() ? image_arg : fs.image;
    // Pixels picked on the features file's own image mean nothing on an image of another size.
    if (!image_arg.empty() && !fs.image.empty() && !fs.image_size && fs.units == "pixels" &&
        std::filesystem::is_regular_file(fs.image)) {
        int fw = 0, fh = 0, aw = 0, ah = 0;
        read_image_size(fs.image, fw, fh);
        read_image_size(image_arg, aw, ah);
        if (fw != aw || fh != ah)
            throw BadInput(fs.path, "its pixel coordinates were picked on " + fs.image + " (" + std::to_string(fw) +
                                        " x " + std::to_string(fh) + "), but --image " + image_arg + " is " +
                                        std::to_string(aw) + " x " + std::to_string(ah) +
                                        ": give an image of the same size, or the points in \"units\": \"uv\"");
    }
    if (!image.empty()) {
        const Image img = read_image(image);
        w = img.width;
        h = img.height;
        if (fs.image_size && ((*fs.image_size)[0] != w || (*fs.image_size)[1] != h))
            throw BadInput(fs.path, "\"image_size\" [" + std::to_string((*fs.image_size)[0]) + ", " +
                                        std::to_string((*fs.image_size)[1]) + "] differs from the size of " + image +
                                        " (" + std::to_string(w) + " x " + std::to_string(h) + ")");
    } else if (fs.image_size) {
        w = (*fs.image_size)[0];
        h = (*fs.image_size)[1];
    } else {
        throw BadInput(fs.path, "no image: give --image, or \"image\" or \"image_size\" in the features file");
    }
    resolve_units(fs, w, h);
    return image;
}

}  // namespace ctmap
