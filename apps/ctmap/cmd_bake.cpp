// `ctmap bake` (issue 42): the photo, aligned by a map's features, painted into the user's own UV
// layout of the mesh (bake/bake_texture.h). Reads the map and ONTO, bakes each UDIM tile, and
// writes the texture(s), the coverage mask and ONTO relinked to the texture, all or nothing.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>

#include "commands.h"
#include "progress.h"
#include "ctmap/bake/bake_texture.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/obj_relink.h"
#include "ctmap/io/read_mesh.h"

namespace ctmap::cli {
namespace {

namespace fs = std::filesystem;

struct BakeArgs {
    std::string map, onto, output, size, image, onto_uv, mask, obj, transfer = "auto";
    int padding = 8;
    double max_distance = -1;
    bool quiet = false;
};

std::string lower_extension(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

/// "W" (square) or "WxH" texels, each 1 to 16384.
void parse_texture_size(const std::string& s, int& w, int& h) {
    auto bad = [&](const std::string& why) { return BadInput("--size", "'" + s + "': " + why + " (give W or WxH texels, each 1 to 16384)"); };
    auto number = [&](const std::string& t) {
        if (t.empty() || t.size() > 5 || t.find_first_not_of("0123456789") != std::string::npos) throw bad("not a whole number");
        const int v = std::stoi(t);
        if (v < 1 || v > 16384) throw bad("out of range");
        return v;
    };
    const std::size_t x = s.find_first_of("xX");
    w = number(s.substr(0, x));
    h = x == std::string::npos ? w : number(s.substr(x + 1));
}

/// A BadInput of bake_texture's ("map" or "onto") named by the file it is about.
[[noreturn]] void rethrow_naming(const BadInput& e, const BakeArgs& a) {
    if (e.file() == "map") throw BadInput(a.map, e.problem());
    if (e.file() == "onto") throw BadInput(a.onto, e.problem());
    if (e.file().empty()) throw BadInput("--size", e.problem());
    throw e;
}

/// Whether two paths name the same file (an output must never be an input).
bool same_file(const std::string& a, const std::string& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

/// `path` with `.<tile>` before its extension (Blender's and Mari's UDIM naming: face.1001.png).
std::string tile_path(const std::string& path, int tile) {
    fs::path p(path);
    return (p.parent_path() / (p.stem().string() + "." + std::to_string(tile) + p.extension().string())).string();
}

/// The map and its photos: an OBJ's material images (one per chart) or a GLB's embedded one; --image overrides.
TexturedMesh read_map(const BakeArgs& a, std::vector<Image>& photos, std::vector<std::string>& photo_names) {
    TexturedMesh map;
    const std::string ext = lower_extension(a.map);
    if (ext == ".obj") {
        std::string image;
        std::vector<ChartMaterial> materials;
        map = read_textured_obj(a.map, &image, &materials);
        if (a.image.empty()) {
            int charts = 1;
            for (int c : map.chart) charts = std::max(charts, c + 1);
            if (charts > 1) {  // a photo per chart, each its material's
                for (int c = 0; c < charts; ++c) {
                    if (c >= int(materials.size()) || materials[std::size_t(c)].image.empty())
                        throw BadInput(a.map, "chart " + std::to_string(c) + (c < int(materials.size()) ? " (material '" +
                                                  materials[std::size_t(c)].name + "')" : std::string()) +
                                                  " names no photo (no map_Kd): give --image to bake every chart from one photo");
                    photo_names.push_back(materials[std::size_t(c)].image);
                }
            } else if (!image.empty()) {
                photo_names.push_back(image);
            } else {
                throw BadInput(a.map, "its material names no photo (no map_Kd in its MTL file): give the photo with --image");
            }
        }
    } else if (ext == ".glb" || ext == ".gltf") {
        GlbTexture texture;
        map = read_glb(a.map, &texture);
        if (a.image.empty()) {
            if (texture.bytes.empty()) throw BadInput(a.map, "embeds no texture: give the photo with --image");
            photos.push_back(decode_image(std::string(texture.bytes.begin(), texture.bytes.end()), a.map + " (its embedded texture)"));
            photo_names.push_back(a.map + " (embedded)");
        }
    } else {
        throw BadInput(a.map, "MAP must be a map ctmap wrote: an OBJ (.obj with its MTL) or a binary glTF (.glb)");
    }
    if (!a.image.empty()) photo_names = {a.image};
    if (photos.empty())
        for (const std::string& p : photo_names) photos.push_back(read_image(p));
    return map;
}

/// ONTO: an OBJ with `vt`, or a glTF with TEXCOORD_0 (or --onto-uv); other formats hold no UVs.
TexturedMesh read_onto(const BakeArgs& a) {
    const std::string ext = lower_extension(a.onto);
    TexturedMesh onto;
    if (ext == ".obj") {
        if (!a.onto_uv.empty())
            throw BadInput("--onto-uv", "'" + a.onto_uv + "': an OBJ holds one UV set (its `vt`); --onto-uv names a glTF attribute such as TEXCOORD_1");
        onto = read_textured_obj(a.onto);
    } else if (ext == ".glb" || ext == ".gltf") {
        onto = read_glb(a.onto, nullptr, a.onto_uv.empty() ? "TEXCOORD_0" : a.onto_uv);
    } else {
        onto.mesh = read_mesh(a.onto);
    }
    if (onto.uvs.empty())
        throw BadInput(a.onto, "has no texture coordinates" +
                                   std::string(a.onto_uv.empty() ? "" : " named " + a.onto_uv) +
                                   ": ONTO must carry its own UV layout (an OBJ with `vt` and `f v/vt`, or a glTF with TEXCOORD_0)");
    return onto;
}

/// The material files an OBJ names (`mtllib` lines), as paths beside it.
std::vector<std::string> mtllibs_of(const std::string& obj) {
    std::vector<std::string> out;
    std::istringstream in(read_input_file(obj, "OBJ file"));
    std::string line;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::size_t s = line.find_first_not_of(" \t");
        if (s == std::string::npos || line.compare(s, 7, "mtllib ") != 0) continue;
        std::string name = line.substr(s + 7);
        name.erase(0, name.find_first_not_of(" \t"));
        if (!name.empty()) out.push_back((fs::path(obj).parent_path() / name).string());
    }
    return out;
}

void write_bytes(const std::string& tmp, const std::string& bytes, const std::string& target) {
    std::ofstream os(tmp, std::ios::binary);
    os << bytes;
    if (!os.flush()) throw InternalError(target + ": could not write the file");
}

int run_bake(const BakeArgs& a) {
    const auto start = std::chrono::steady_clock::now();
    if (lower_extension(a.output) != ".png") throw BadInput(a.output, "the texture is written as PNG: give -o a .png name");
    if (!a.mask.empty() && lower_extension(a.mask) != ".png") throw BadInput(a.mask, "the mask is written as PNG: give --mask a .png name");
    if (!a.obj.empty() && lower_extension(a.obj) != ".obj") throw BadInput(a.obj, "--obj writes an OBJ: give it a .obj name");
    if (!a.obj.empty() && lower_extension(a.onto) != ".obj")
        throw BadInput("--obj", "ONTO (" + a.onto + ") is not an OBJ: --obj writes ONTO's own OBJ lines again, so ONTO must be one");
    for (const std::string& out : {a.output, a.mask, a.obj})
        for (const std::string& in : {a.map, a.onto, a.image})
            if (!out.empty() && !in.empty() && same_file(out, in))
                throw BadInput(out, "is an input of this bake: ctmap never writes over its inputs");
    int width = 0, height = 0;
    if (!a.size.empty()) parse_texture_size(a.size, width, height);

    std::vector<Image> photos;
    std::vector<std::string> photo_names;
    TexturedMesh map = read_map(a, photos, photo_names);
    for (const std::string& p : photo_names)
        if (same_file(a.output, p)) throw BadInput(a.output, "is the map's photo: ctmap never writes over its inputs");
    const TexturedMesh onto = read_onto(a);
    std::vector<int> tiles;
    try {
        tiles = udim_tiles(onto);
    } catch (const BadInput& e) {
        rethrow_naming(e, a);
    }

    // Every file this bake reads, and every one it would write: no output may be an input, nor
    // two outputs the same file.
    std::vector<std::string> inputs = {a.map, a.onto};
    for (const std::string& p : photo_names) inputs.push_back(p);
    for (const std::string& obj : {a.map, a.onto})
        if (lower_extension(obj) == ".obj")
            for (const std::string& m : mtllibs_of(obj)) inputs.push_back(m);
    OutputSet outputs;
    struct TileOut {
        int tile;
        std::string texture, mask, texture_tmp, mask_tmp;
    };
    std::vector<TileOut> outs;
    const bool udim = tiles != std::vector<int>{1001};
    for (int t : tiles) {
        TileOut o{t, udim ? tile_path(a.output, t) : a.output, a.mask.empty() ? "" : (udim ? tile_path(a.mask, t) : a.mask), "", ""};
        o.texture_tmp = outputs.add(o.texture);
        if (!o.mask.empty()) o.mask_tmp = outputs.add(o.mask);
        outs.push_back(o);
    }
    std::string obj_tmp, mtl_tmp, mtl_path;
    if (!a.obj.empty()) {
        mtl_path = (fs::path(a.obj).parent_path() / (fs::path(a.obj).stem().string() + ".mtl")).string();
        obj_tmp = outputs.add(a.obj);
        mtl_tmp = outputs.add(mtl_path);
    }
    std::vector<std::string> written;
    for (const TileOut& o : outs) {
        written.push_back(o.texture);
        if (!o.mask.empty()) written.push_back(o.mask);
    }
    if (!a.obj.empty()) written.push_back(a.obj), written.push_back(mtl_path);
    for (std::size_t i = 0; i < written.size(); ++i) {
        for (const std::string& in : inputs)
            if (same_file(written[i], in)) throw BadInput(written[i], "is an input of this bake: ctmap never writes over its inputs");
        for (std::size_t j = 0; j < i; ++j)
            if (same_file(written[i], written[j])) throw BadInput(written[i], "is given as two outputs of this bake");
    }

    Progress progress(!a.quiet, isatty(fileno(stderr)), "ctmap bake: ");
    std::mutex progress_mutex;
    BakeOptions opt;
    opt.width = width, opt.height = height, opt.padding = a.padding, opt.max_distance = a.max_distance;
    opt.transfer = a.transfer == "exact" ? BakeTransfer::exact : a.transfer == "closest" ? BakeTransfer::closest : BakeTransfer::automatic;
    std::vector<BakeStats> stats;
    int tex_w = 0, tex_h = 0;
    for (TileOut& o : outs) {
        opt.tile = Vec2((o.tile - 1001) % 10, (o.tile - 1001) / 10);
        const std::string stage = udim ? "tile " + std::to_string(o.tile) + " rows" : "rows";
        opt.progress = [&](int done, int total) {
            std::lock_guard<std::mutex> lock(progress_mutex);
            progress(stage, done, total);
        };
        BakeResult r;
        try {
            r = bake_texture(map, photos, onto, opt);
        } catch (const BadInput& e) {
            rethrow_naming(e, a);
        }
        tex_w = r.texture.width, tex_h = r.texture.height;
        write_bytes(o.texture_tmp, encode_png(r.texture), o.texture);
        if (!o.mask.empty()) {
            Image m;
            m.width = r.texture.width, m.height = r.texture.height, m.channels = 1;
            m.pixels.resize(r.covered.size());
            for (std::size_t i = 0; i < r.covered.size(); ++i) m.pixels[i] = r.covered[i] ? 255 : 0;
            write_bytes(o.mask_tmp, encode_png(m), o.mask);
        }
        stats.push_back(r.stats);
    }
    progress.clear();
    if (!a.obj.empty()) {
        const std::string text = read_input_file(a.onto, "OBJ file");
        write_bytes(obj_tmp, relink_obj(text, fs::path(mtl_path).filename().string(), "ctmap_baked"), a.obj);
        std::string mtl = mtl_text({{"ctmap_baked", outs.front().texture}}, a.obj);
        if (udim) {
            mtl += "# UDIM tiles:";
            for (const TileOut& o : outs) mtl += " " + fs::path(o.texture).filename().string();
            mtl += "\n";
        }
        write_bytes(mtl_tmp, mtl, mtl_path);
    }
    outputs.commit_all();

    long long covered = 0, twice = 0, far = 0, padded = 0;
    for (const BakeStats& s : stats) covered += s.covered, twice += s.written_twice, far += s.too_far, padded += s.padded;
    if (twice > 0)
        std::cerr << "ctmap bake: warning: " << a.onto << ": " << twice
                  << " texels lie in two UV triangles (overlapping UV islands): the later face's colour was kept\n";
    if (!a.quiet) {
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        std::cout << "baked " << covered << " texels of " << tex_w << " x " << tex_h
                  << (udim ? " in " + std::to_string(outs.size()) + " UDIM tiles" : std::string()) << " ("
                  << (stats.front().exact ? "exact: ONTO is the map's input mesh"
                                          : "closest point on the map, within " + fixed(stats.front().max_distance, 6) +
                                                "; not exact: " + stats.front().not_exact)
                  << "), " << padded << " padded";
        if (far > 0) std::cout << ", " << far << " left empty (farther than " << fixed(stats.front().max_distance, 6) << " from the map)";
        std::cout << ", in " << fixed(ms / 1000.0, 2) << " s\n";
        for (const TileOut& o : outs) std::cout << "wrote " << o.texture << (o.mask.empty() ? "" : ", " + o.mask) << "\n";
        if (!a.obj.empty()) std::cout << "wrote " << a.obj << ", " << mtl_path << " (ONTO's lines unchanged, its material the texture)\n";
    }
    return kExitOk;
}

}  // namespace

Command add_bake_command(CLI::App& app) {
    auto args = std::make_shared<BakeArgs>();
    CLI::App* sub = app.add_subcommand(
        "bake", "Paint the photo, aligned by a map's features, into another UV layout of the mesh (your own): exact "
                "when ONTO is the mesh the map was computed from, else by the closest point of the map");
    sub->add_option("MAP", args->map, "a map ctmap wrote: OBJ + MTL (the photo its material names) or GLB (the photo embedded)")->required();
    sub->add_option("ONTO", args->onto, "the mesh with its own UVs: OBJ with vt, or glTF/GLB with TEXCOORD_0")->required();
    sub->add_option("-o,--output", args->output, "the texture to write (PNG; UDIM layouts: one per tile, name.1001.png, ...)")->required();
    sub->add_option("--size", args->size, "W or WxH texels (default: the photo's size)");
    sub->add_option("--padding", args->padding, "texels each island's border colours grow outward, against seams in mip-maps")
        ->check(CLI::Range(0, 256))
        ->capture_default_str();
    sub->add_option("--image", args->image, "the photo (PNG/JPEG); overrides the map's material or embedded texture");
    sub->add_option("--onto-uv", args->onto_uv, "glTF ONTO: the UV attribute to bake into (e.g. TEXCOORD_1)");
    sub->add_option("--mask", args->mask, "also write a PNG of the texels the UV triangles cover (255) and not (0)");
    sub->add_option("--obj", args->obj,
                    "also write ONTO again as OBJ + MTL with the texture as its material, its v/vt/vn/f lines byte for byte");
    sub->add_option("--max-distance", args->max_distance,
                    "closest transfer: texels farther than this from the map are left empty (default: 1% of ONTO's bounding-box diagonal)")
        ->check(CLI::NonNegativeNumber);
    sub->add_option("--transfer", args->transfer, "auto (exact when ONTO is the map's input mesh) | exact (else an error) | closest")
        ->check(CLI::IsMember({"auto", "exact", "closest"}))
        ->capture_default_str();
    sub->add_flag("-q,--quiet", args->quiet, "print nothing on success");
    return {sub, [args] { return run_bake(*args); }};
}

}  // namespace ctmap::cli
