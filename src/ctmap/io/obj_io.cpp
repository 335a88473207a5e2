#include "ctmap/io/obj_io.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "ctmap/errors.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/vertex_normals.h"

namespace ctmap {
namespace {
/// The comment lines that record, per face, the input face it lies in (TexturedMesh::input_face).
constexpr std::string_view kInputFaceTag = "#ctmap_input_face ";
constexpr std::size_t kInputFacesPerLine = 20;
}  // namespace

namespace {

namespace fs = std::filesystem;

void put_double(std::string& out, double v) {
    char buf[64];
    auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest form that round-trips
    out.append(buf, end);
}

/// `keyword` and the three coordinates of `p`, each in its shortest round-trip form.
void put_line(std::string& out, const char* keyword, const Vec3& p) {
    out += keyword;
    put_double(out, p.x());
    out += ' ';
    put_double(out, p.y());
    out += ' ';
    put_double(out, p.z());
    out += '\n';
}

std::string relative_to(const std::string& target, const std::string& from_file) {
    fs::path base = fs::absolute(fs::path(from_file)).parent_path();
    fs::path t = fs::absolute(fs::path(target));
    fs::path rel = t.lexically_relative(base);
    return rel.empty() ? t.string() : rel.string();
}

void check_or_throw(std::ofstream& os, const std::string& path) {
    if (!os.flush()) throw InternalError(path + ": could not write the file");
}

}  // namespace

void write_obj(const TexturedMesh& tm, const std::string& obj_path, const std::string& image, OutputSet& outputs) {
    const std::vector<ChartMaterial> one{{"ctmap_texture", image}};
    if (std::any_of(tm.chart.begin(), tm.chart.end(), [](int c) { return c != 0; })) {
        TexturedMesh single = tm;  // one image for every chart (e.g. an OBJ read with several materials)
        single.chart.assign(single.mesh.faces.size(), 0);
        return write_obj(single, obj_path, one, outputs);
    }
    write_obj(tm, obj_path, one, outputs);
}

std::string mtl_text(const std::vector<ChartMaterial>& materials, const std::string& obj_path) {
    std::string s = "# written by ctmap\n";
    for (std::size_t c = 0; c < materials.size(); ++c) {
        s += (c ? "\n" : "") + std::string("newmtl ") + materials[c].name + "\nKa 1 1 1\nKd 1 1 1\nKs 0 0 0\nillum 1\n";
        if (!materials[c].image.empty()) s += "map_Kd " + relative_to(materials[c].image, obj_path) + "\n";
    }
    return s;
}

void write_obj(const TexturedMesh& tm, const std::string& obj_path, const std::vector<ChartMaterial>& materials,
               OutputSet& outputs) {
    for (int c : tm.chart)
        if (c < 0 || c >= int(materials.size()))
            throw BadInput(obj_path, "chart " + std::to_string(c) + " has no material (" +
                                         std::to_string(materials.size()) + " given)");
    const bool has_uv = !tm.uvs.empty();
    const fs::path obj(obj_path);
    const std::string mtl_name = obj.stem().string() + ".mtl";
    const std::string mtl_path = (obj.parent_path() / mtl_name).string();
    const std::string obj_tmp = outputs.add(obj_path);
    const std::string mtl_tmp = outputs.add(mtl_path);

    std::string s;
    s.reserve(tm.mesh.positions.size() * 60 + tm.uvs.size() * 40 + tm.mesh.faces.size() * 40);
    s += "# written by ctmap: UVs per face corner, UV = (x / W, 1 - y / H)\n";
    s += "mtllib " + mtl_name + "\n";
    for (const Vec3& p : tm.mesh.positions) put_line(s, "v ", p);
    for (const Vec2& t : tm.uvs) {
        s += "vt ";
        put_double(s, t.x());
        s += ' ';
        put_double(s, t.y());
        s += '\n';
    }
    for (const Vec3& n : vertex_normals(tm.mesh)) put_line(s, "vn ", n);  // smooth shading: vn i is vertex i's normal
    const bool groups = tm.patch.size() == tm.mesh.faces.size();
    const bool charts = tm.chart.size() == tm.mesh.faces.size();
    if (!charts) s += "usemtl " + materials.at(0).name + "\n";
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f) {
        if (charts && (f == 0 || tm.chart[f] != tm.chart[f - 1])) s += "usemtl " + materials[tm.chart[f]].name + '\n';
        if (groups && (f == 0 || tm.patch[f] != tm.patch[f - 1])) s += "g patch_" + std::to_string(tm.patch[f]) + '\n';
        s += 'f';
        for (int k = 0; k < 3; ++k) {
            const std::string v = std::to_string(tm.mesh.faces[f][k] + 1);
            s += ' ' + v + '/';
            if (has_uv) s += std::to_string(tm.uv_faces[f][k] + 1);
            s += '/' + v;
        }
        s += '\n';
    }
    if (tm.input_face.size() == tm.mesh.faces.size()) {
        s += "# per face above, in order: the face of the input mesh it lies in (read by ctmap bake)\n";
        for (std::size_t f = 0; f < tm.input_face.size(); f += kInputFacesPerLine) {
            s += kInputFaceTag;
            for (std::size_t g = f; g < std::min(tm.input_face.size(), f + kInputFacesPerLine); ++g)
                s += (g == f ? "" : " ") + std::to_string(tm.input_face[g]);
            s += '\n';
        }
    }
    {
        std::ofstream os(obj_tmp, std::ios::binary);
        os << s;
        check_or_throw(os, obj_path);
    }
    {
        std::ofstream os(mtl_tmp, std::ios::binary);
        os << mtl_text(materials, obj_path);
        check_or_throw(os, mtl_path);
    }
}

void write_obj(const TexturedMesh& mesh, const std::string& obj_path, const std::string& image) {
    OutputSet outputs;
    write_obj(mesh, obj_path, image, outputs);
    outputs.commit_all();
}

namespace {

struct LineReader {
    const std::string& path;
    int line_no = 0;
    [[noreturn]] void fail(const std::string& what) const {
        throw BadInput(path, "line " + std::to_string(line_no) + ": " + what);
    }
};

double parse_double(const char*& p, const char* end, const LineReader& r) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    double v = 0;
    auto [next, ec] = std::from_chars(p, end, v);
    if (ec != std::errc() ) r.fail("expected a number");
    if (!std::isfinite(v)) r.fail("non-finite number (NaN or infinity)");
    p = next;
    return v;
}

/// Resolves a 1-based (or negative, relative) OBJ index against `count` elements.
int resolve_index(long long i, std::size_t count, const char* what, const LineReader& r) {
    long long k = i > 0 ? i - 1 : static_cast<long long>(count) + i;
    if (i == 0 || k < 0 || k >= static_cast<long long>(count))
        r.fail(std::string(what) + " index " + std::to_string(i) + " is out of range (there are " +
               std::to_string(count) + ")");
    return static_cast<int>(k);
}

}  // namespace

TexturedMesh read_textured_obj(const std::string& path, std::string* image, std::vector<ChartMaterial>* materials) {
    check_input_file(path, "OBJ file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw BadInput(path, "cannot be opened for reading");

    TexturedMesh tm;
    std::vector<std::array<long long, 2>> corners;  // raw (v, vt) per corner of the current face
    std::string mtllib;
    std::string line;
    LineReader r{path};
    bool any_uv_face = false, any_plain_face = false;
    int group_patch = -1;           // from `g patch_<id>` (ctmap's own files)
    std::vector<std::string> used_materials;  // in order of first use: a chart each (issue 13)
    int chart = 0;
    bool all_faces_grouped = true;
    while (std::getline(in, line)) {
        ++r.line_no;
        if (r.line_no == 1) line.erase(0, utf8_bom_length(line));  // a byte-order mark, as Windows editors write
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const char* p = line.data();
        const char* end = p + line.size();
        while (p < end && (*p == ' ' || *p == '\t')) ++p;
        if (std::size_t(end - p) > kInputFaceTag.size() && std::string_view(p, kInputFaceTag.size()) == kInputFaceTag) {
            p += kInputFaceTag.size();
            while (true) {
                while (p < end && (*p == ' ' || *p == '\t')) ++p;
                if (p == end) break;
                int f = -1;
                auto [q, ecode] = std::from_chars(p, end, f);
                if (ecode != std::errc() || f < 0) r.fail("malformed `" + std::string(kInputFaceTag) + "` line");
                tm.input_face.push_back(f);
                p = q;
            }
            continue;
        }
        if (p == end || *p == '#') continue;
        if (line.find('\0') != std::string::npos) r.fail("binary data in a text OBJ file");
        auto starts = [&](const char* kw) {
            const std::size_t n = std::strlen(kw);
            return std::size_t(end - p) > n && std::strncmp(p, kw, n) == 0 && (p[n] == ' ' || p[n] == '\t');
        };
        if (starts("v")) {
            p += 1;
            const double x = parse_double(p, end, r), y = parse_double(p, end, r), z = parse_double(p, end, r);
            tm.mesh.positions.emplace_back(x, y, z);
        } else if (starts("vt")) {
            p += 2;
            const double u = parse_double(p, end, r), v = parse_double(p, end, r);
            tm.uvs.emplace_back(u, v);
        } else if (starts("f")) {
            p += 1;
            corners.clear();
            while (true) {
                while (p < end && (*p == ' ' || *p == '\t')) ++p;
                if (p == end) break;
                long long v = 0, t = 0;
                auto [n1, e1] = std::from_chars(p, end, v);
                if (e1 != std::errc()) r.fail("malformed face corner");
                p = n1;
                if (p < end && *p == '/') {
                    ++p;
                    if (p < end && *p != '/') {
                        auto [n2, e2] = std::from_chars(p, end, t);
                        if (e2 != std::errc()) r.fail("malformed texture index in face corner");
                        p = n2;
                    }
                    if (p < end && *p == '/') {  // normal index: read and ignored
                        ++p;
                        long long n = 0;
                        auto [n3, e3] = std::from_chars(p, end, n);
                        if (e3 != std::errc()) r.fail("malformed normal index in face corner");
                        p = n3;
                    }
                }
                if (p < end && *p != ' ' && *p != '\t') r.fail("malformed face corner");
                corners.push_back({v, t});
            }
            if (corners.size() < 3) r.fail("a face needs at least 3 corners");
            std::vector<int> vi, ti;
            for (auto [v, t] : corners) {
                vi.push_back(resolve_index(v, tm.mesh.positions.size(), "vertex", r));
                ti.push_back(t ? resolve_index(t, tm.uvs.size(), "texture coordinate", r) : -1);
            }
            const bool has_t = ti[0] >= 0;
            for (int t : ti)
                if ((t >= 0) != has_t) r.fail("a face mixes corners with and without texture coordinates");
            (has_t ? any_uv_face : any_plain_face) = true;
            for (std::size_t k = 1; k + 1 < vi.size(); ++k) {
                tm.mesh.faces.push_back({vi[0], vi[k], vi[k + 1]});
                tm.uv_faces.push_back({ti[0], ti[k], ti[k + 1]});
                tm.patch.push_back(group_patch);
                tm.chart.push_back(chart);
            }
            all_faces_grouped = all_faces_grouped && group_patch >= 0;
        } else if (starts("g")) {
            std::string rest(p + 1, end);
            rest.erase(0, rest.find_first_not_of(" \t"));
            int id = -1;
            if (rest.rfind("patch_", 0) == 0) {
                auto [q, ecode] = std::from_chars(rest.data() + 6, rest.data() + rest.size(), id);
                if (ecode != std::errc() || q != rest.data() + rest.size() || id < 0) id = -1;
            }
            group_patch = id;
        } else if (starts("usemtl")) {
            std::string rest(p + 6, end);
            rest.erase(0, rest.find_first_not_of(" \t"));
            const auto it = std::find(used_materials.begin(), used_materials.end(), rest);
            chart = int(it - used_materials.begin());
            if (it == used_materials.end()) used_materials.push_back(rest);
        } else if (starts("mtllib")) {
            std::string rest(p + 6, end);
            rest.erase(0, rest.find_first_not_of(" \t"));
            mtllib = rest;
        }
    }
    if (tm.mesh.positions.empty()) throw BadInput(path, "no vertices (is this an OBJ file?)");
    if (tm.mesh.faces.empty()) throw BadInput(path, "no faces");
    if (any_uv_face && any_plain_face) throw BadInput(path, "some faces have texture coordinates and some do not");
    if (!any_uv_face) {  // `vt` lines no face uses: no map (writers index uv_faces per face)
        tm.uv_faces.clear();
        tm.uvs.clear();
    }
    if (!all_faces_grouped) tm.patch.clear();
    if (tm.input_face.size() != tm.mesh.faces.size()) tm.input_face.clear();  // not one per face: not ctmap's record
    if (used_materials.empty()) used_materials.push_back("");
    if (materials) {
        materials->clear();
        for (const std::string& n : used_materials) materials->push_back({n, ""});
    }
    if (image || materials) {
        if (image) image->clear();
        if (!mtllib.empty()) {
            const fs::path mtl = fs::path(path).parent_path() / mtllib;
            std::ifstream m(mtl);
            std::string l, current;
            while (std::getline(m, l)) {
                if (!l.empty() && l.back() == '\r') l.pop_back();
                std::istringstream ls(l);
                std::string kw;
                ls >> kw;
                if (kw == "newmtl") std::getline(ls >> std::ws, current);
                if (kw == "map_Kd") {
                    std::string name;
                    std::getline(ls >> std::ws, name);
                    const std::string file = (mtl.parent_path() / name).lexically_normal().string();
                    if (image) *image = file;
                    if (materials)
                        for (ChartMaterial& cm : *materials)
                            if (cm.name == current) cm.image = file;
                }
            }
        }
    }
    return tm;
}

}  // namespace ctmap
