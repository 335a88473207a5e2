#include "ctmap/io/glb_io.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>

#include "ctmap/errors.h"
#include "ctmap/io/glb_container.h"
#include "ctmap/io/printable.h"
#include "ctmap/io/image.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/vertex_normals.h"

namespace ctmap {
namespace {

template <class T>
int append(std::vector<unsigned char>& buf, const std::vector<T>& data) {
    while (buf.size() % 4) buf.push_back(0);  // accessors must be aligned to their component size
    const int offset = int(buf.size());
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
    buf.insert(buf.end(), bytes, bytes + data.size() * sizeof(T));
    return offset;
}

int add_view(tinygltf::Model& m, int offset, std::size_t length, int target) {
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = std::size_t(offset);
    v.byteLength = length;
    v.target = target;
    m.bufferViews.push_back(v);
    return int(m.bufferViews.size()) - 1;
}

std::string mime_of(const std::string& path, const std::vector<unsigned char>& bytes) {
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG", 4) == 0) return "image/png";
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return "image/jpeg";
    throw BadInput(path, "the texture for a glTF file must be a PNG or JPEG");
}

/// `p` as glTF's 32-bit floats. \throw BadInput if a coordinate does not fit in a float.
Eigen::Vector3f float_position(const Vec3& p, int vertex, const std::string& path) {
    const Eigen::Vector3f f = p.cast<float>();
    if (!f.allFinite())
        throw BadInput(path, "vertex " + std::to_string(vertex) + " has a coordinate out of the range of the " +
                                 "32-bit floats glTF stores (|x| > 3.4e38); scale the mesh or write .obj");
    return f;
}

/// glTF's vertices: one per distinct (vertex, uv) corner pair, since glTF has one UV per vertex.
/// glTF vertex i is input vertex i with the UV of its first corner, so the input order is kept
/// (DESIGN §3); the copies of a vertex whose corners carry other UVs come after the first |V|.
struct GlbVertices {
    std::vector<std::pair<int, int>> source;  ///< (input vertex, uv index or -1) per glTF vertex
    std::vector<std::uint32_t> indices;       ///< three per face
};

GlbVertices split_vertices(const TexturedMesh& tm) {
    const bool has_uv = !tm.uvs.empty();
    GlbVertices out;
    for (int v = 0; v < tm.mesh.num_vertices(); ++v) out.source.emplace_back(v, -1);
    if (has_uv)
        for (std::size_t f = tm.mesh.faces.size(); f-- > 0;)  // backwards: the first corner wins
            for (int k = 3; k-- > 0;) out.source[tm.mesh.faces[f][k]].second = tm.uv_faces[f][k];
    std::map<std::pair<int, int>, std::uint32_t> vertex_of;
    for (std::size_t i = 0; i < out.source.size(); ++i) vertex_of.emplace(out.source[i], std::uint32_t(i));
    out.indices.reserve(tm.mesh.faces.size() * 3);
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const std::pair<int, int> corner(tm.mesh.faces[f][k], has_uv ? tm.uv_faces[f][k] : -1);
            auto [it, fresh] = vertex_of.emplace(corner, std::uint32_t(out.source.size()));
            if (fresh) out.source.push_back(corner);
            out.indices.push_back(it->second);
        }
    return out;
}

/// Adds `mesh` to `m` as its one node of its one scene and writes the binary glTF to `path` (a
/// temporary registered in `outputs`).
void write_single_mesh(tinygltf::Model& m, const tinygltf::Mesh& mesh, const std::string& path, OutputSet& outputs) {
    m.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    m.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    m.scenes.push_back(scene);
    m.defaultScene = 0;
    const std::string tmp = outputs.add(path);
    std::ofstream os(tmp, std::ios::binary);
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&m, os, false, true) || !os.flush())
        throw InternalError(path + ": could not write the glTF file");
}

int add_accessor(tinygltf::Model& m, int view, int ctype, std::size_t count, int type) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = ctype;
    a.count = count;
    a.type = type;
    m.accessors.push_back(a);
    return int(m.accessors.size()) - 1;
}

/// A float VEC3 vertex attribute accessor over `data` (3 floats per vertex), with min and max.
int add_vec3(tinygltf::Model& m, const std::vector<float>& data) {
    auto& buf = m.buffers[0].data;
    const int a = add_accessor(m, add_view(m, append(buf, data), data.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                               TINYGLTF_COMPONENT_TYPE_FLOAT, data.size() / 3, TINYGLTF_TYPE_VEC3);
    std::vector<double> lo(3, 0), hi(3, 0);
    for (std::size_t i = 0; i < data.size(); ++i) {
        const std::size_t k = i % 3;
        lo[k] = i < 3 ? data[i] : std::min(lo[k], double(data[i]));
        hi[k] = i < 3 ? data[i] : std::max(hi[k], double(data[i]));
    }
    m.accessors[a].minValues = lo;
    m.accessors[a].maxValues = hi;
    return a;
}

}  // namespace

void write_glb(const TexturedMesh& tm, const std::string& path, const std::string& image, OutputSet& outputs) {
    const std::vector<ChartMaterial> one{{"ctmap_texture", image}};
    if (std::any_of(tm.chart.begin(), tm.chart.end(), [](int c) { return c != 0; })) {
        TexturedMesh single = tm;  // one image for every chart (e.g. an OBJ read with several materials)
        single.chart.assign(single.mesh.faces.size(), 0);
        return write_glb(single, path, one, outputs);
    }
    write_glb(tm, path, one, outputs);
}

namespace {

/// The image file `image` as a glTF image of `m` (its bytes in the buffer). A JPEG turned by its
/// EXIF orientation is embedded upright as PNG: the UVs refer to the upright picture, and viewers
/// do not all honour EXIF inside glTF.
int add_image(tinygltf::Model& m, const std::string& image) {
    std::ifstream in(image, std::ios::binary);
    if (!in) throw BadInput(image, "cannot read the texture image");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (exif_orientation(std::string(bytes.begin(), bytes.end())) != 1) {
        const std::string png = encode_png(read_image(image));
        bytes.assign(png.begin(), png.end());
    }
    tinygltf::Image img;
    img.mimeType = mime_of(image, bytes);
    img.name = std::filesystem::path(image).stem().string();
    img.bufferView = add_view(m, append(m.buffers[0].data, bytes), bytes.size(), 0);
    m.images.push_back(img);
    if (m.samplers.empty()) {
        tinygltf::Sampler s;
        s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
        s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
        s.wrapS = s.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
        m.samplers.push_back(s);
    }
    tinygltf::Texture tex;
    tex.source = int(m.images.size()) - 1;
    tex.sampler = 0;
    m.textures.push_back(tex);
    return int(m.textures.size()) - 1;
}

}  // namespace

void write_glb(const TexturedMesh& tm, const std::string& path, const std::vector<ChartMaterial>& materials,
               OutputSet& outputs) {
    for (int c : tm.chart)
        if (c < 0 || c >= int(materials.size()))
            throw BadInput(path, "chart " + std::to_string(c) + " has no material (" + std::to_string(materials.size()) + " given)");
    const bool has_uv = !tm.uvs.empty();
    const GlbVertices vertices = split_vertices(tm);
    const std::vector<std::uint32_t>& idx = vertices.indices;
    std::vector<float> pos, uv, nrm;
    Eigen::AlignedBox3f box;
    const std::vector<Vec3> normals = vertex_normals(tm.mesh);
    for (auto [v, t] : vertices.source) {
        const Eigen::Vector3f p = float_position(tm.mesh.positions[v], v, path);
        pos.insert(pos.end(), {p.x(), p.y(), p.z()});
        nrm.insert(nrm.end(), {float(normals[v].x()), float(normals[v].y()), float(normals[v].z())});
        box.extend(p);
        if (!has_uv) continue;
        const Vec2 w = t >= 0 ? tm.uvs[t] : Vec2(0, 0);  // a vertex on no face has no UV
        uv.insert(uv.end(), {float(w.x()), float(1.0 - w.y())});
    }

    tinygltf::Model m;
    m.asset.version = "2.0";
    m.asset.generator = "ctmap";
    m.buffers.emplace_back();
    auto& buf = m.buffers[0].data;

    // One primitive per chart (issue 13), all on the same vertex attributes.
    tinygltf::Primitive shared;
    shared.mode = TINYGLTF_MODE_TRIANGLES;
    const int pos_acc = add_accessor(m, add_view(m, append(buf, pos), pos.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_FLOAT, pos.size() / 3, TINYGLTF_TYPE_VEC3);
    m.accessors[pos_acc].minValues = {double(box.min().x()), double(box.min().y()), double(box.min().z())};
    m.accessors[pos_acc].maxValues = {double(box.max().x()), double(box.max().y()), double(box.max().z())};
    shared.attributes["POSITION"] = pos_acc;
    shared.attributes["NORMAL"] =  // smooth shading in three.js and Blender
        add_accessor(m, add_view(m, append(buf, nrm), nrm.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                     TINYGLTF_COMPONENT_TYPE_FLOAT, nrm.size() / 3, TINYGLTF_TYPE_VEC3);
    if (has_uv)
        shared.attributes["TEXCOORD_0"] =
            add_accessor(m, add_view(m, append(buf, uv), uv.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                         TINYGLTF_COMPONENT_TYPE_FLOAT, uv.size() / 2, TINYGLTF_TYPE_VEC2);

    tinygltf::Mesh mesh;
    mesh.name = "ctmap";
    std::map<std::string, int> texture_of;  // image path -> texture (charts may share an image)
    const int charts = tm.chart.size() == tm.mesh.faces.size() ? int(materials.size()) : 1;
    for (int c = 0; c < charts; ++c) {
        std::vector<std::uint32_t> chart_idx;
        if (charts == 1) chart_idx = idx;
        else
            for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f)
                if (tm.chart[f] == c) chart_idx.insert(chart_idx.end(), idx.begin() + 3 * f, idx.begin() + 3 * f + 3);
        if (chart_idx.empty()) continue;
        tinygltf::Primitive prim = shared;
        prim.indices = add_accessor(m, add_view(m, append(buf, chart_idx), chart_idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, chart_idx.size(), TINYGLTF_TYPE_SCALAR);
        tinygltf::Material mat;
        mat.name = materials[c].name;
        mat.pbrMetallicRoughness.metallicFactor = 0.0;
        mat.pbrMetallicRoughness.roughnessFactor = 1.0;
        mat.doubleSided = true;
        if (!materials[c].image.empty() && has_uv) {
            auto it = texture_of.find(materials[c].image);
            if (it == texture_of.end()) it = texture_of.emplace(materials[c].image, add_image(m, materials[c].image)).first;
            mat.pbrMetallicRoughness.baseColorTexture.index = it->second;
        }
        m.materials.push_back(mat);
        prim.material = int(m.materials.size()) - 1;
        mesh.primitives.push_back(prim);
    }
    write_single_mesh(m, mesh, path, outputs);
}

void write_morph_glb(const TriMesh& base, const std::vector<Vec3>& target, const std::string& path, OutputSet& outputs,
                     double seconds) {
    if (target.size() != base.positions.size()) throw InternalError(path + ": the morph target has another vertex count");
    tinygltf::Model m;
    m.asset.version = "2.0";
    m.asset.generator = "ctmap morph";
    m.buffers.emplace_back();
    TriMesh end = base;
    end.positions = target;
    const std::vector<Vec3> n0 = vertex_normals(base), n1 = vertex_normals(end);
    std::vector<float> pos, nrm, dpos, dnrm;
    for (std::size_t v = 0; v < base.positions.size(); ++v) {
        const Eigen::Vector3f p = float_position(base.positions[v], int(v), path);
        const Eigen::Vector3f q = float_position(target[v], int(v), path);
        pos.insert(pos.end(), {p.x(), p.y(), p.z()});
        const Eigen::Vector3f d = q - p;
        if (!d.allFinite())
            throw BadInput(path, "vertex " + std::to_string(v) + " moves farther than 32-bit floats hold; scale the meshes");
        dpos.insert(dpos.end(), {d.x(), d.y(), d.z()});
        const Eigen::Vector3f a = n0[v].cast<float>(), b = n1[v].cast<float>();
        nrm.insert(nrm.end(), {a.x(), a.y(), a.z()});
        dnrm.insert(dnrm.end(), {b.x() - a.x(), b.y() - a.y(), b.z() - a.z()});
    }
    std::vector<std::uint32_t> idx;
    for (const Tri& t : base.faces) idx.insert(idx.end(), {std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});

    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = add_vec3(m, pos);
    prim.attributes["NORMAL"] = add_vec3(m, nrm);
    prim.targets.push_back({{"POSITION", add_vec3(m, dpos)}, {"NORMAL", add_vec3(m, dnrm)}});
    auto& buf = m.buffers[0].data;
    prim.indices = add_accessor(m, add_view(m, append(buf, idx), idx.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, idx.size(), TINYGLTF_TYPE_SCALAR);
    tinygltf::Material mat;
    mat.name = "ctmap_morph";
    mat.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    mat.doubleSided = true;
    m.materials.push_back(mat);
    prim.material = 0;

    // The weight from 0 to 1 and back, linearly: time [0, s, 2s] -> weight [0, 1, 0].
    const std::vector<float> times{0.0f, float(seconds), float(2 * seconds)}, weights{0.0f, 1.0f, 0.0f};
    tinygltf::Animation anim;
    anim.name = "morph";
    tinygltf::AnimationSampler sampler;
    sampler.input = add_accessor(m, add_view(m, append(buf, times), times.size() * 4, 0), TINYGLTF_COMPONENT_TYPE_FLOAT,
                                 times.size(), TINYGLTF_TYPE_SCALAR);
    m.accessors[sampler.input].minValues = {0.0};
    m.accessors[sampler.input].maxValues = {2 * seconds};
    sampler.output = add_accessor(m, add_view(m, append(buf, weights), weights.size() * 4, 0),
                                  TINYGLTF_COMPONENT_TYPE_FLOAT, weights.size(), TINYGLTF_TYPE_SCALAR);
    sampler.interpolation = "LINEAR";
    anim.samplers.push_back(sampler);
    tinygltf::AnimationChannel channel;
    channel.sampler = 0;
    channel.target_node = 0;
    channel.target_path = "weights";
    anim.channels.push_back(channel);
    m.animations.push_back(anim);

    tinygltf::Mesh mesh;
    mesh.name = "ctmap_morph";
    mesh.primitives.push_back(prim);
    mesh.weights = {0.0};
    tinygltf::Value::Object extras;
    extras["targetNames"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(std::string("target"))});
    mesh.extras = tinygltf::Value(extras);
    write_single_mesh(m, mesh, path, outputs);
}

void write_glb(const TexturedMesh& mesh, const std::string& path, const std::string& image) {
    OutputSet outputs;
    write_glb(mesh, path, image, outputs);
    outputs.commit_all();
}

namespace {

/// The buffer view `index` of `m`, checked to lie inside its buffer.
const tinygltf::BufferView& checked_view(const tinygltf::Model& m, int index, const std::string& path) {
    if (index < 0 || index >= int(m.bufferViews.size())) throw BadInput(path, "a buffer view index is out of range");
    const tinygltf::BufferView& v = m.bufferViews[index];
    if (v.buffer < 0 || v.buffer >= int(m.buffers.size()) ||
        v.byteOffset + v.byteLength > m.buffers[v.buffer].data.size())
        throw BadInput(path, "buffer view " + std::to_string(index) + " runs past its buffer");
    return v;
}

template <class T>
std::vector<T> read_accessor(const tinygltf::Model& m, int index, int ctype, int type, const std::string& path) {
    if (index < 0 || index >= int(m.accessors.size())) throw BadInput(path, "missing accessor");
    const tinygltf::Accessor& a = m.accessors[index];
    if (a.componentType != ctype || a.type != type || a.bufferView < 0)
        throw BadInput(path, "unsupported accessor layout (ctmap reads what it writes: float positions/UVs, uint32 indices)");
    const tinygltf::BufferView& v = checked_view(m, a.bufferView, path);
    const int n = tinygltf::GetNumComponentsInType(type);
    const std::size_t stride = v.byteStride ? v.byteStride : n * sizeof(T);
    const auto& data = m.buffers[v.buffer].data;
    std::vector<T> out(a.count * n);
    for (std::size_t i = 0; i < a.count; ++i) {
        const std::size_t at = v.byteOffset + a.byteOffset + i * stride;
        if (at + n * sizeof(T) > data.size()) throw BadInput(path, "accessor runs past its buffer");
        std::memcpy(&out[i * n], data.data() + at, n * sizeof(T));
    }
    return out;
}

/// The first material's base-colour texture, if its image is embedded in a buffer view.
GlbTexture embedded_texture(const tinygltf::Model& m, const std::string& path) {
    GlbTexture t;
    if (m.materials.empty()) return t;
    const int tex = m.materials[0].pbrMetallicRoughness.baseColorTexture.index;
    if (tex < 0 || tex >= int(m.textures.size())) return t;
    const int src = m.textures[tex].source;
    if (src < 0 || src >= int(m.images.size()) || m.images[src].bufferView < 0) return t;
    const tinygltf::Image& img = m.images[src];
    const tinygltf::BufferView& v = checked_view(m, img.bufferView, path);
    const auto& data = m.buffers[v.buffer].data;
    t.mime_type = img.mimeType;
    t.bytes.assign(data.begin() + v.byteOffset, data.begin() + v.byteOffset + v.byteLength);
    return t;
}

bool has_glb_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = char(std::tolower((unsigned char)c));
    return ext == ".glb";
}

}  // namespace

TexturedMesh read_glb(const std::string& path, GlbTexture* texture, const std::string& uv_attribute) {
    check_input_file(path, "glTF file");
    tinygltf::Model m;
    tinygltf::TinyGLTF gltf;
    std::string err, warn;
    // The texture is taken as stored bytes (embedded_texture); tinygltf's own decoding of it (stb
    // on a buffer view it does not bound: ASan, issue 17's fuzzing) is not needed.
    gltf.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                           void*) { return true; },
                        nullptr);
    // External buffers and images (a .gltf's `uri`) are read as ctmap reads every input: regular
    // files only, each checked (tinygltf's own reader took a folder's size as 2^63 and asked for
    // that much memory: a fuzz finding), and nothing is written.
    tinygltf::FsCallbacks fs{};
    fs.FileExists = [](const std::string& p, void*) {
        std::error_code ec;
        return std::filesystem::is_regular_file(p, ec);
    };
    fs.ExpandFilePath = [](const std::string& p, void*) { return p; };
    fs.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& p, void*) {
        try {
            const std::string bytes = read_input_file(p, "glTF buffer file");
            out->assign(bytes.begin(), bytes.end());
            return true;
        } catch (const BadInput& e) {
            if (err) *err += e.what();
            return false;
        }
    };
    fs.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
        if (err) *err += "the glTF reader writes no file";
        return false;
    };
    gltf.SetFsCallbacks(fs);
    bool ok = false;
    if (has_glb_extension(path)) {
        // Read once, the container checked (glb_container.h), then parsed from memory.
        const std::string bytes = read_input_file(path, "glTF file");
        check_glb_container(bytes, path);
        ok = gltf.LoadBinaryFromMemory(&m, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                       static_cast<unsigned int>(bytes.size()),
                                       std::filesystem::path(path).parent_path().string());
    } else {
        ok = gltf.LoadASCIIFromFile(&m, &err, &warn, path);
    }
    if (!ok) throw BadInput(path, "not a readable glTF file: " + printable(err, 300));
    if (m.meshes.empty() || m.meshes[0].primitives.empty()) throw BadInput(path, "no mesh in the glTF file");
    // Every primitive of the first mesh, primitive k as chart k (ctmap writes one per chart,
    // issue 13, on shared vertex attributes: an attribute accessor is read once).
    TexturedMesh tm;
    std::map<int, std::pair<int, int>> base_of;  // POSITION accessor -> its first vertex in tm, its count
    bool any_uv = false, any_plain = false;
    for (std::size_t k = 0; k < m.meshes[0].primitives.size(); ++k) {
        const tinygltf::Primitive& p = m.meshes[0].primitives[k];
        if (!p.attributes.count("POSITION")) throw BadInput(path, "a primitive has no POSITION");
        const int position_accessor = p.attributes.at("POSITION");
        auto [it, fresh] = base_of.emplace(position_accessor, std::make_pair(tm.mesh.num_vertices(), 0));
        const int base = it->second.first;
        if (fresh) {
            const auto pos = read_accessor<float>(m, position_accessor, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, path);
            for (std::size_t i = 0; i < pos.size(); i += 3) {
                if (!std::isfinite(pos[i]) || !std::isfinite(pos[i + 1]) || !std::isfinite(pos[i + 2]))
                    throw BadInput(path, "vertex " + std::to_string(i / 3) + " has a non-finite coordinate (NaN or infinity)");
                tm.mesh.positions.emplace_back(pos[i], pos[i + 1], pos[i + 2]);
            }
            if (p.attributes.count(uv_attribute)) {
                const auto uv = read_accessor<float>(m, p.attributes.at(uv_attribute), TINYGLTF_COMPONENT_TYPE_FLOAT,
                                                     TINYGLTF_TYPE_VEC2, path);
                if (uv.size() / 2 != pos.size() / 3) throw BadInput(path, uv_attribute + " and POSITION have different counts");
                for (std::size_t i = 0; i < uv.size(); i += 2) tm.uvs.emplace_back(uv[i], 1.0 - double(uv[i + 1]));
                any_uv = true;
            } else {
                any_plain = true;
            }
        }
        if (fresh) it->second.second = tm.mesh.num_vertices() - base;
        const int count = it->second.second;
        const auto idx = read_accessor<std::uint32_t>(m, p.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, path);
        for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
            for (std::uint32_t c = 0; c < 3; ++c)
                if (idx[i + c] >= std::uint32_t(count))
                    throw BadInput(path, "index out of range");
            tm.mesh.faces.push_back({base + int(idx[i]), base + int(idx[i + 1]), base + int(idx[i + 2])});
            tm.chart.push_back(int(k));
        }
    }
    if (any_uv && any_plain) throw BadInput(path, "some primitives have texture coordinates and some do not");
    if (any_uv) tm.uv_faces = tm.mesh.faces;
    if (texture) *texture = embedded_texture(m, path);
    return tm;
}

}  // namespace ctmap
