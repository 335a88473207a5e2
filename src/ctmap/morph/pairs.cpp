#include "ctmap/morph/pairs.h"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ctmap/errors.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/json_document.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

using json = nlohmann::json;

/// Parses one end ("source" or "target") of the pair `who`; adds what is wrong to `problems`.
PairEnd parse_end(const json& pair, const char* side, const std::string& who, std::vector<std::string>& problems) {
    PairEnd end;
    if (!pair.contains(side) || !pair[side].is_object()) {
        problems.push_back(who + ": missing object \"" + side + "\" ({\"vertex\": i} or {\"point\": [x, y, z]})");
        return end;
    }
    const json& e = pair[side];
    const bool has_vertex = e.contains("vertex"), has_point = e.contains("point");
    if (has_vertex == has_point) {
        problems.push_back(who + ": \"" + side + "\" must give exactly one of \"vertex\" or \"point\"");
    } else if (has_vertex) {
        const json& v = e["vertex"];
        if (!v.is_number_integer() || v.get<long long>() < 0 || v.get<long long>() > 2000000000LL)
            problems.push_back(who + ": " + side + " \"vertex\" must be a non-negative integer index, got " + v.dump());
        else
            end.vertex = v.get<int>();
    } else {
        double p[3];
        if (!read_number_array(e["point"], 3, p)) problems.push_back(who + ": " + side + " \"point\" must be [x, y, z]");
        else if (!all_finite(p, 3)) problems.push_back(who + ": " + side + " \"point\" has a non-finite coordinate");
        else end.point = Vec3(p[0], p[1], p[2]);
    }
    return end;
}

void throw_if_any(const std::vector<std::string>& problems, const std::string& path) {
    if (problems.empty()) return;
    std::string msg = "the pairs file is invalid:";
    for (const std::string& p : problems) msg += "\n  - " + p;
    throw BadInput(path, msg);
}

}  // namespace

PairSet read_pairs(const std::string& path) {
    check_input_file(path, "pairs file");
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return parse_pairs(ss.str(), path);
}

PairSet parse_pairs(const std::string& text, const std::string& path) {
    const json doc = parse_json_document(text, path, "pairs file");
    if (!doc.is_object() || !doc.contains("pairs"))
        throw BadInput(path, "a pairs file holds a JSON object with a \"pairs\" array (ctmap morph --help)");
    std::vector<std::string> problems;
    if (doc.contains("units") && doc["units"] != "mesh")
        problems.push_back("wrong units " + doc["units"].dump() + ": pairs are given in the meshes' own units, \"mesh\"");
    const json& list = doc["pairs"];
    if (!list.is_array()) problems.push_back("\"pairs\" must be an array");
    else if (list.empty()) problems.push_back("\"pairs\" is empty: at least one pair is needed");
    PairSet out;
    out.path = path;
    if (list.is_array()) {
        int index = 0;
        for (const json& p : list) {
            const std::string label = "pair #" + std::to_string(index++);
            if (!p.is_object()) {
                problems.push_back(label + " is not an object");
                continue;
            }
            FeaturePair fp;
            if (!p.contains("name") || !p["name"].is_string() || p["name"].get<std::string>().empty())
                problems.push_back(label + ": \"name\" must be a non-empty string");
            else
                fp.name = p["name"].get<std::string>();
            const std::string who = fp.name.empty() ? label : "pair " + quoted_name(fp.name);
            fp.source = parse_end(p, "source", who, problems);
            fp.target = parse_end(p, "target", who, problems);
            out.pairs.push_back(std::move(fp));
        }
    }
    throw_if_any(problems, path);

    std::map<std::string, int> names;
    std::map<int, std::string> source_vertex, target_vertex;
    for (const FeaturePair& p : out.pairs) {
        if (!names.emplace(p.name, 0).second) problems.push_back("two pairs are named " + quoted_name(p.name));
        if (p.source.vertex >= 0) {
            auto [it, fresh] = source_vertex.emplace(p.source.vertex, p.name);
            if (!fresh)
                problems.push_back("pairs " + quoted_name(it->second) + " and " + quoted_name(p.name) +
                                   " are at the same source vertex " + std::to_string(p.source.vertex));
        }
        if (p.target.vertex >= 0) {
            auto [it, fresh] = target_vertex.emplace(p.target.vertex, p.name);
            if (!fresh)
                problems.push_back("pairs " + quoted_name(it->second) + " and " + quoted_name(p.name) +
                                   " are at the same target vertex " + std::to_string(p.target.vertex));
        }
    }
    throw_if_any(problems, path);
    return out;
}

std::string pairs_to_json(const PairSet& set) {
    json list = json::array();
    auto end = [](const PairEnd& e) {
        if (e.vertex >= 0) return json{{"vertex", e.vertex}};
        return json{{"point", {e.point->x(), e.point->y(), e.point->z()}}};
    };
    for (const FeaturePair& p : set.pairs) list.push_back({{"name", p.name}, {"source", end(p.source)}, {"target", end(p.target)}});
    return json{{"units", "mesh"}, {"pairs", list}}.dump(2) + "\n";
}

}  // namespace ctmap
