#include "ctmap/io/chart_features.h"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "ctmap/errors.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/json_document.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

using json = nlohmann::json;

/// Where a feature is on the mesh, as the file gives it (a vertex or a point), for comparing.
std::string place_of(const json& f) {
    if (f.contains("vertex")) return "vertex " + f["vertex"].dump();
    if (f.contains("point")) return "point " + f["point"].dump();
    return "";
}

void throw_problems(const std::string& path, const std::vector<std::string>& problems) {
    if (problems.empty()) return;
    std::string msg = "the features file's charts are invalid:";
    for (const std::string& p : problems) msg += "\n  - " + p;
    throw BadInput(path, msg);
}

}  // namespace

bool has_charts(const std::string& text, const std::string& path) {
    const json doc = parse_json_document(text, path, "features file");
    return doc.is_object() && doc.contains("charts");
}

ChartFile read_chart_features(const std::string& path) {
    check_input_file(path, "features file");
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_chart_features(ss.str(), path);
}

ChartFile parse_chart_features(const std::string& text, const std::string& path) {
    const json doc = parse_json_document(text, path, "features file");
    if (!doc.is_object() || !doc.contains("charts") || !doc["charts"].is_array() || doc["charts"].empty())
        throw BadInput(path, "\"charts\" must be a non-empty array of charts");
    if (doc.contains("features"))
        throw BadInput(path, "give the features inside each chart (\"charts\"[i].\"features\"), not beside \"charts\"");
    std::vector<std::string> problems;
    const json& charts = doc["charts"];

    // Names, and each feature's mesh place over all charts.
    std::map<std::string, std::pair<std::string, std::string>> place;  // feature -> (place, chart that gave it)
    std::set<std::string> chart_names;
    std::vector<std::string> name_of(charts.size());
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const json& ch = charts[c];
        const std::string label = "chart #" + std::to_string(c);
        if (!ch.is_object()) {
            problems.push_back(label + " is not an object");
            continue;
        }
        if (!ch.contains("name") || !ch["name"].is_string() || ch["name"].get<std::string>().empty())
            problems.push_back(label + ": \"name\" must be a non-empty string");
        else if (!chart_names.insert(name_of[c] = ch["name"].get<std::string>()).second)
            problems.push_back("the chart name " + quoted_name(name_of[c]) + " is used by more than one chart");
        else if (name_of[c].find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
                 std::string::npos)
            problems.push_back("the chart name " + quoted_name(name_of[c]) +
                               " may hold only letters, digits, '_' and '-' (it names the chart's material in the OBJ)");
        if (name_of[c].empty()) name_of[c] = label;
        if (!ch.contains("features") || !ch["features"].is_array()) {
            problems.push_back("chart " + quoted_name(name_of[c]) + ": \"features\" must be an array");
            continue;
        }
        for (const json& f : ch["features"]) {
            if (!f.is_object() || !f.contains("name") || !f["name"].is_string()) continue;  // parse_features names it
            const std::string p = place_of(f), name = f["name"].get<std::string>();
            if (p.empty()) continue;
            auto [it, fresh] = place.emplace(name, std::make_pair(p, name_of[c]));
            if (!fresh && it->second.first != p)
                problems.push_back("feature " + quoted_name(name) + " is at " + printable(it->second.first) + " in chart " +
                                   quoted_name(it->second.second) + " but at " + printable(p) + " in chart " + quoted_name(name_of[c]) +
                                   ": a feature is one place on the mesh in every chart");
        }
    }
    throw_problems(path, problems);

    ChartFile out;
    out.path = path;
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const json& ch = charts[c];
        // The chart as a features file of its own, places filled in, read by parse_features.
        json sub = json::object();
        for (const char* key : {"units", "image", "image_size"})
            if (ch.contains(key)) sub[key] = ch[key];
            else if (doc.contains(key)) sub[key] = doc[key];
        sub["features"] = json::array();
        for (json f : ch["features"]) {
            if (f.is_object() && f.contains("name") && f["name"].is_string() && place_of(f).empty()) {
                const auto it = place.find(f["name"].get<std::string>());
                if (it == place.end()) {
                    problems.push_back("chart " + quoted_name(name_of[c]) + ": feature " + quoted_name(f["name"].get<std::string>()) +
                                       " has no \"vertex\" or \"point\" in any chart");
                    continue;
                }
                for (const json& g : charts)
                    for (const json& h : g["features"])
                        if (h.is_object() && h.value("name", json()) == f["name"] && !place_of(h).empty()) {
                            if (h.contains("vertex")) f["vertex"] = h["vertex"];
                            else f["point"] = h["point"];
                            goto filled;
                        }
            filled:;
            }
            sub["features"].push_back(f);
        }
        ChartFeatures cf;
        cf.name = name_of[c];
        try {
            cf.features = parse_features(sub.dump(), path);
        } catch (const BadInput& e) {
            problems.push_back("chart " + quoted_name(cf.name) + ": " + e.problem());
            continue;
        }
        if (ch.contains("border")) {
            if (!ch["border"].is_array()) {
                problems.push_back("chart " + quoted_name(cf.name) + ": \"border\" must be an array of feature names");
                continue;
            }
            std::set<std::string> known, seen;
            for (const Feature& f : cf.features.features) known.insert(f.name);
            for (const json& b : ch["border"]) {
                if (!b.is_string()) {
                    problems.push_back("chart " + quoted_name(cf.name) + ": \"border\" holds " + printable(b.dump()) + ", not a feature name");
                    continue;
                }
                const std::string n = b.get<std::string>();
                if (!known.count(n))
                    problems.push_back("chart " + quoted_name(cf.name) + ": border feature " + quoted_name(n) +
                                       " is not one of the chart's features");
                else if (!seen.insert(n).second)
                    problems.push_back("chart " + quoted_name(cf.name) + ": border feature " + quoted_name(n) + " is listed twice");
                cf.border.push_back(n);
            }
            if (cf.border.size() < 3)
                problems.push_back("chart " + quoted_name(cf.name) + ": \"border\" needs at least 3 features, has " +
                                   std::to_string(cf.border.size()));
        } else if (charts.size() > 1) {
            problems.push_back("chart " + quoted_name(cf.name) +
                               ": \"border\" is missing (only a file's one chart may be bounded by the mesh border)");
        }
        out.charts.push_back(std::move(cf));
    }
    throw_problems(path, problems);
    return out;
}

std::vector<std::string> resolve_chart_images(ChartFile& cf, std::vector<std::array<int, 2>>& sizes) {
    std::vector<std::string> images;
    sizes.clear();
    for (ChartFeatures& c : cf.charts) {
        int w = 0, h = 0;
        try {
            images.push_back(resolve_feature_image(c.features, "", w, h));
        } catch (const BadInput& e) {
            throw BadInput(cf.path, "chart " + quoted_name(c.name) + ": " + e.problem());
        }
        sizes.push_back({w, h});
    }
    return images;
}

}  // namespace ctmap
