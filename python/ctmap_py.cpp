// Python bindings of ctmap (issue 16): numpy arrays in and out, the report as a dict, ctmap's
// errors as Python exceptions (BadInput -> ValueError, InternalError -> RuntimeError), and the
// GIL released while a map is computed, so maps run in parallel Python threads.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "ctmap/bake/bake_texture.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_charts.h"
#include "ctmap/map_texture.h"

namespace py = pybind11;
using namespace ctmap;

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Ints = py::array_t<long long, py::array::c_style | py::array::forcecast>;

/// A JSON value as the Python object json.loads would give.
py::object to_python(const nlohmann::json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

/// V (n x 3 doubles, finite) and F (m x 3 indices in [0, n)) as a TriMesh. \throw BadInput.
TriMesh mesh_from(const Doubles& V, const Ints& F) {
    if (V.ndim() != 2 || V.shape(1) != 3) throw BadInput("V", "must be an n x 3 array of vertex positions");
    if (F.ndim() != 2 || F.shape(1) != 3) throw BadInput("F", "must be an m x 3 array of vertex indices (triangles)");
    TriMesh m;
    const auto v = V.unchecked<2>();
    for (py::ssize_t i = 0; i < V.shape(0); ++i) {
        const Vec3 p(v(i, 0), v(i, 1), v(i, 2));
        if (!p.allFinite()) throw BadInput("V", "vertex " + std::to_string(i) + " has a non-finite coordinate");
        m.positions.push_back(p);
    }
    const auto f = F.unchecked<2>();
    for (py::ssize_t i = 0; i < F.shape(0); ++i) {
        Tri t;
        for (int k = 0; k < 3; ++k) {
            const long long x = f(i, k);
            if (x < 0 || x >= V.shape(0))
                throw BadInput("F", "face " + std::to_string(i) + " has vertex index " + std::to_string(x) +
                                        " out of range (there are " + std::to_string(V.shape(0)) + " vertices)");
            t[k] = int(x);
        }
        m.faces.push_back(t);
    }
    return m;
}

/// The features (dicts with name, vertex or point, image) for map_texture. \throw BadInput naming the feature.
std::vector<MapFeature> features_from(const py::list& features, const std::string& units, std::optional<std::pair<int, int>> size) {
    if (units != "pixels" && units != "uv") throw BadInput("units", "must be \"pixels\" or \"uv\"");
    if (units == "pixels" && (!size || size->first <= 0 || size->second <= 0))
        throw BadInput("image_size", "give image_size=(width, height) for features in pixels (or units=\"uv\")");
    std::vector<MapFeature> out;
    std::set<std::string> names;
    for (const py::handle h : features) {
        if (!py::isinstance<py::dict>(h))
            throw BadInput("features", "feature #" + std::to_string(out.size()) + " is not a dict");
        const py::dict d = py::reinterpret_borrow<py::dict>(h);
        MapFeature f;
        if (!d.contains("name")) throw BadInput("features", "feature #" + std::to_string(out.size()) + " has no \"name\"");
        f.name = py::str(d["name"]);
        const std::string who = "feature \"" + f.name + "\"";
        try {
        if (!names.insert(f.name).second) throw BadInput("features", "two features are named \"" + f.name + "\"");
        if (d.contains("vertex") == d.contains("point"))
            throw BadInput("features", who + ": give exactly one of \"vertex\" or \"point\"");
        if (d.contains("vertex")) {
            const long long v = d["vertex"].cast<long long>();
            if (v < 0) throw BadInput("features", who + ": vertex " + std::to_string(v) + " is negative");
            f.vertex = int(std::min<long long>(v, 2000000000LL));
        } else {
            const auto p = d["point"].cast<std::vector<double>>();
            if (p.size() != 3 || !Vec3(p[0], p[1], p[2]).allFinite())
                throw BadInput("features", who + ": \"point\" must be 3 finite numbers");
            f.point = Vec3(p[0], p[1], p[2]);
        }
        if (!d.contains("image")) throw BadInput("features", who + ": no \"image\" point");
        const auto q = d["image"].cast<std::vector<double>>();
        if (q.size() != 2 || !std::isfinite(q[0]) || !std::isfinite(q[1]))
            throw BadInput("features", who + ": \"image\" must be 2 finite numbers");
        f.uv = units == "uv" ? Vec2(q[0], q[1]) : image_to_uv(Vec2(q[0], q[1]), size->first, size->second);
        if (!(f.uv.x() >= 0 && f.uv.x() <= 1 && f.uv.y() >= 0 && f.uv.y() <= 1))
            throw BadInput("features", who + ": its image point lies outside the image");
        } catch (const py::cast_error&) {
            throw BadInput("features", who + ": \"vertex\" must be an integer, \"point\" and \"image\" lists of numbers");
        }
        out.push_back(f);
    }
    return out;
}

/// Rows of N numbers (a Vec3, Vec2 or Tri per row) as an n x N numpy array of T.
template <class T, int N, class Row>
py::array_t<T> rows_array(const std::vector<Row>& rows) {
    py::array_t<T> a({py::ssize_t(rows.size()), py::ssize_t(N)});
    auto m = a.template mutable_unchecked<2>();
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (int k = 0; k < N; ++k) m(py::ssize_t(i), k) = T(rows[i][k]);
    return a;
}

py::array_t<double> positions_array(const std::vector<Vec3>& p) { return rows_array<double, 3>(p); }
py::array_t<double> uv_array(const std::vector<Vec2>& p) { return rows_array<double, 2>(p); }
py::array_t<int> faces_array(const std::vector<Tri>& f) { return rows_array<int, 3>(f); }

/// A map's UVs per face corner: m x 3 x 2, corner k of face f at [f, k].
py::array_t<double> corner_uvs(const TexturedMesh& tm) {
    py::array_t<double> corners({py::ssize_t(tm.uv_faces.size()), py::ssize_t(3), py::ssize_t(2)});
    auto c = corners.mutable_unchecked<3>();
    for (std::size_t f = 0; f < tm.uv_faces.size(); ++f)
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 2; ++d) c(py::ssize_t(f), k, d) = tm.uvs[tm.uv_faces[f][k]][d];
    return corners;
}

/// A TexturedMesh with per-vertex UVs from numpy arrays. \throw BadInput.
TexturedMesh textured_from(const Doubles& V, const Ints& F, const Doubles& UV) {
    TriMesh m = mesh_from(V, F);
    if (UV.ndim() != 2 || UV.shape(1) != 2 || UV.shape(0) != V.shape(0))
        throw BadInput("UV", "must be an n x 2 array, one UV per vertex");
    std::vector<Vec2> uv;
    const auto u = UV.unchecked<2>();
    for (py::ssize_t i = 0; i < UV.shape(0); ++i) {
        uv.emplace_back(u(i, 0), u(i, 1));
        if (!uv.back().allFinite()) throw BadInput("UV", "the UV of vertex " + std::to_string(i) + " is not finite");
    }
    return TexturedMesh::with_vertex_uvs(std::move(m), std::move(uv));
}

py::dict map_texture_py(const Doubles& V, const Ints& F, const py::list& features, std::optional<std::pair<int, int>> image_size,
                        const std::string& units, const std::string& refine, const std::string& border,
                        const std::string& border_mode, int iterations, double tolerance, double snap) {
    const TriMesh mesh = mesh_from(V, F);
    require_disc(compute_topology(mesh), "the mesh (V, F)", NotDiscAdvice::cut_open);
    const std::vector<MapFeature> fs = features_from(features, units, image_size);
    if (refine != "isometric" && refine != "paper" && refine != "none")
        throw BadInput("refine", "must be \"isometric\", \"paper\" or \"none\"");
    if (border != "auto" && border != "given") throw BadInput("border", "must be \"auto\" or \"given\"");
    if (border_mode != "free" && border_mode != "fixed" && border_mode != "unbounded")
        throw BadInput("border_mode", "must be \"free\", \"fixed\" or \"unbounded\"");
    MapOptions o;  // as `ctmap map` sets them (apps/ctmap/cmd_map.cpp)
    o.refine = refine != "none";
    o.refine_mode = refine == "paper" ? RefineMode::paper : RefineMode::isometric;
    o.auto_border = border == "auto";
    o.isometric.border = border_mode == "fixed" ? BorderMode::fixed : BorderMode::free;
    o.isometric.keep_in_box = border_mode != "unbounded";
    o.isometric.max_iterations = iterations;
    o.isometric.tolerance = tolerance;
    o.snap = snap;
    MapResult r;
    {
        py::gil_scoped_release release;  // the map touches no Python object
        r = map_texture(mesh, fs, o);
    }
    const TexturedMesh tm = r.textured();
    const py::array_t<double> corners = corner_uvs(tm);
    py::dict out;
    out["V"] = positions_array(r.cut.mesh.positions);
    out["F"] = faces_array(r.cut.mesh.faces);
    out["UV"] = uv_array(r.uv);
    out["UV_corners"] = corners;
    out["chart"] = py::array_t<int>(py::ssize_t(tm.chart.size()), tm.chart.data());
    out["feature_vertex"] = r.cut.feature_vertex;
    out["input_face"] = py::array_t<int>(py::ssize_t(r.input_face.size()), r.input_face.data());
    out["certificate"] = to_python(certificate_to_json(r.certificate));
    return out;
}

py::dict certify_py(const Doubles& V, const Ints& F, const Doubles& UV, std::vector<int> feature_vertex,
                    const std::optional<Doubles>& feature_uv) {
    const TexturedMesh tm = textured_from(V, F, UV);
    std::vector<Vec2> fuv;
    if (feature_uv) {
        if (feature_uv->ndim() != 2 || feature_uv->shape(1) != 2) throw BadInput("feature_uv", "must be a k x 2 array");
        const auto u = feature_uv->unchecked<2>();
        for (py::ssize_t i = 0; i < feature_uv->shape(0); ++i) fuv.emplace_back(u(i, 0), u(i, 1));
    }
    if (fuv.size() != feature_vertex.size()) throw BadInput("feature_uv", "give one UV per feature vertex");
    for (int v : feature_vertex)
        if (v < 0 || v >= tm.mesh.num_vertices()) throw BadInput("feature_vertex", "vertex " + std::to_string(v) + " is out of range");
    Certificate c;
    {
        py::gil_scoped_release release;
        c = certify(tm, feature_vertex, fuv);
    }
    return to_python(certificate_to_json(c));
}

py::dict map_charts_py(const Doubles& V, const Ints& F, const py::list& charts, const std::string& refine,
                       const std::string& border_mode, int iterations) {
    const TriMesh mesh = mesh_from(V, F);
    std::vector<ChartInput> in;
    for (const py::handle h : charts) {
        if (!py::isinstance<py::dict>(h)) throw BadInput("charts", "chart #" + std::to_string(in.size()) + " is not a dict");
        const py::dict d = py::reinterpret_borrow<py::dict>(h);
        ChartInput ci;
        if (!d.contains("name") || !d.contains("features") || !d.contains("image_size"))
            throw BadInput("charts", "chart #" + std::to_string(in.size()) + " needs \"name\", \"features\" and \"image_size\"");
        ci.name = py::str(d["name"]);
        const auto size = d["image_size"].cast<std::pair<int, int>>();
        ci.features = features_from(d["features"].cast<py::list>(), "pixels", size);
        if (d.contains("border")) ci.border = d["border"].cast<std::vector<std::string>>();
        in.push_back(std::move(ci));
    }
    if (refine != "isometric" && refine != "paper" && refine != "none")
        throw BadInput("refine", "must be \"isometric\", \"paper\" or \"none\"");
    if (border_mode != "free" && border_mode != "fixed") throw BadInput("border_mode", "must be \"free\" or \"fixed\"");
    MapOptions o;  // as `ctmap map` sets them for charts (apps/ctmap/cmd_map_charts.cpp)
    o.refine = refine != "none";
    o.refine_mode = refine == "paper" ? RefineMode::paper : RefineMode::isometric;
    o.isometric.border = border_mode == "fixed" ? BorderMode::fixed : BorderMode::free;
    o.isometric.max_iterations = iterations;
    ChartsResult r;
    {
        py::gil_scoped_release release;
        r = map_charts(mesh, in, o);
    }
    const TexturedMesh& tm = r.textured;
    const py::array_t<double> corners = corner_uvs(tm);
    py::dict out;
    out["V"] = positions_array(tm.mesh.positions);
    out["F"] = faces_array(tm.mesh.faces);
    out["UV_corners"] = corners;
    out["chart"] = py::array_t<int>(py::ssize_t(tm.chart.size()), tm.chart.data());
    out["input_face"] = py::array_t<int>(py::ssize_t(tm.input_face.size()), tm.input_face.data());
    std::vector<std::string> names;
    for (const ChartMap& cm : r.charts) names.push_back(cm.name);
    if (r.rest.faces > 0) names.push_back("rest");
    out["chart_names"] = names;
    py::list occ;
    for (const FeatureOccurrence& f : r.occurrences) {
        py::dict d;
        d["name"] = f.name, d["chart"] = f.chart, d["vertex"] = f.vertex, d["uv"] = std::vector<double>{f.uv.x(), f.uv.y()};
        occ.append(d);
    }
    out["occurrences"] = occ;
    out["certificate"] = to_python(certificate_to_json(r.certificate));
    return out;
}

/// ONTO's UVs: n x 2 (one per vertex) or m x 3 x 2 (per face corner). \throw BadInput.
void set_uvs_from(TexturedMesh& t, const Doubles& UV, const char* name) {
    const py::ssize_t n = py::ssize_t(t.mesh.positions.size()), m = py::ssize_t(t.mesh.faces.size());
    if (UV.ndim() == 2 && UV.shape(0) == n && UV.shape(1) == 2) {
        const auto u = UV.unchecked<2>();
        for (py::ssize_t i = 0; i < n; ++i) t.uvs.emplace_back(u(i, 0), u(i, 1));
        t.uv_faces = t.mesh.faces;
    } else if (UV.ndim() == 3 && UV.shape(0) == m && UV.shape(1) == 3 && UV.shape(2) == 2) {
        const auto u = UV.unchecked<3>();
        for (py::ssize_t f = 0; f < m; ++f) {
            Tri tri;
            for (int k = 0; k < 3; ++k) tri[k] = int(t.uvs.size()), t.uvs.emplace_back(u(f, k, 0), u(f, k, 1));
            t.uv_faces.push_back(tri);
        }
    } else {
        throw BadInput(name, "must be n x 2 (one UV per vertex) or m x 3 x 2 (per face corner)");
    }
    for (const Vec2& q : t.uvs)
        if (!q.allFinite()) throw BadInput(name, "has a non-finite UV");
    t.chart.assign(t.mesh.faces.size(), 0);
}

/// An H x W x 3 or 4 uint8 array as an RGBA Image. \throw BadInput.
Image image_from(const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& a) {
    if (a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4) || a.shape(0) < 1 || a.shape(1) < 1)
        throw BadInput("photo", "must be an H x W x 3 (RGB) or H x W x 4 (RGBA) uint8 array");
    Image im;
    im.height = int(a.shape(0)), im.width = int(a.shape(1)), im.channels = 4;
    im.pixels.resize(std::size_t(im.width) * std::size_t(im.height) * 4, 255);
    const auto v = a.unchecked<3>();
    for (py::ssize_t y = 0; y < a.shape(0); ++y)
        for (py::ssize_t x = 0; x < a.shape(1); ++x)
            for (py::ssize_t k = 0; k < a.shape(2); ++k) im.pixels[(std::size_t(y) * std::size_t(im.width) + std::size_t(x)) * 4 + std::size_t(k)] = v(y, x, k);
    return im;
}

py::dict bake_py(const py::dict& map, const py::object& photo,
                 const Doubles& V, const Ints& F, const Doubles& UV, std::optional<std::pair<int, int>> size, int padding,
                 double max_distance, const std::string& transfer, std::optional<int> tile) {
    for (const char* k : {"V", "F"})
        if (!map.contains(k)) throw BadInput("map", std::string("has no \"") + k + "\" (give the dict map_texture or map_charts returned)");
    if (!map.contains("UV") && !map.contains("UV_corners"))
        throw BadInput("map", "has no \"UV_corners\" (give the dict map_texture or map_charts returned)");
    TexturedMesh m;
    m.mesh = mesh_from(map["V"].cast<Doubles>(), map["F"].cast<Ints>());
    set_uvs_from(m, map.contains("UV_corners") ? map["UV_corners"].cast<Doubles>() : map["UV"].cast<Doubles>(), "map[\"UV\"]");
    if (map.contains("input_face")) {
        const auto f = map["input_face"].cast<std::vector<int>>();
        if (f.size() == m.mesh.faces.size()) m.input_face = f;
    }
    if (map.contains("chart")) {
        const auto ch = map["chart"].cast<std::vector<int>>();
        if (ch.size() == m.mesh.faces.size()) m.chart = ch;
    }
    TexturedMesh onto;
    onto.mesh = mesh_from(V, F);
    set_uvs_from(onto, UV, "UV");
    std::vector<int> tiles;
    try {
        tiles = udim_tiles(onto);
    } catch (const BadInput& e) {
        throw BadInput("UV", e.problem());
    }
    const int t = tile.value_or(tiles.size() == 1 ? tiles.front() : 0);
    if (std::find(tiles.begin(), tiles.end(), t) == tiles.end()) {
        std::string list;
        for (int x : tiles) list += (list.empty() ? "" : ", ") + std::to_string(x);
        throw BadInput("tile", "the UVs lie in the UDIM tiles " + list + ": give tile= one of them");
    }
    if (transfer != "auto" && transfer != "exact" && transfer != "closest")
        throw BadInput("transfer", "must be \"auto\", \"exact\" or \"closest\"");
    if (padding < 0) throw BadInput("padding", "must be >= 0");
    BakeOptions o;
    if (size) {
        if (size->first < 1 || size->second < 1 || size->first > 16384 || size->second > 16384)
            throw BadInput("size", "each side must be 1 to 16384 texels");
        o.width = size->first, o.height = size->second;
    }
    o.padding = padding, o.max_distance = max_distance;
    o.tile = Vec2((t - 1001) % 10, (t - 1001) / 10);
    o.transfer = transfer == "exact" ? BakeTransfer::exact : transfer == "closest" ? BakeTransfer::closest : BakeTransfer::automatic;
    using Bytes = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>;
    std::vector<Image> photos;  // one, or one per chart (map["chart"])
    if (py::isinstance<py::list>(photo) || py::isinstance<py::tuple>(photo))
        for (const py::handle h : photo) photos.push_back(image_from(h.cast<Bytes>()));
    else
        photos.push_back(image_from(photo.cast<Bytes>()));
    BakeResult r;
    {
        py::gil_scoped_release release;
        r = bake_texture(m, photos, onto, o);
    }
    py::array_t<std::uint8_t> tex({py::ssize_t(r.texture.height), py::ssize_t(r.texture.width), py::ssize_t(4)});
    std::copy(r.texture.pixels.begin(), r.texture.pixels.end(), tex.mutable_data());
    py::array_t<bool> covered({py::ssize_t(r.texture.height), py::ssize_t(r.texture.width)});
    std::transform(r.covered.begin(), r.covered.end(), covered.mutable_data(), [](std::uint8_t b) { return b != 0; });
    py::dict out;
    out["texture"] = tex;
    out["covered"] = covered;
    out["exact"] = r.stats.exact;
    out["not_exact"] = r.stats.not_exact;
    out["covered_texels"] = r.stats.covered;
    out["written_twice"] = r.stats.written_twice;
    out["too_far"] = r.stats.too_far;
    out["padded"] = r.stats.padded;
    return out;
}

}  // namespace

PYBIND11_MODULE(ctmap, m) {
    m.doc() = "ctmap: constrained texture mapping (Guo et al.), exact features and a certified injective map";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const BadInput& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const InternalError& e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
        }
    });
    m.def("read_mesh", [](const std::string& path) {
        const TriMesh mesh = read_mesh(path);
        return py::make_tuple(positions_array(mesh.positions), faces_array(mesh.faces));
    }, py::arg("path"), "Reads an OFF/OBJ/PLY/STL mesh: returns (V, F), V float64 n x 3, F int32 m x 3 (0-based).");
    m.def("map_texture", &map_texture_py, py::arg("V"), py::arg("F"), py::arg("features"), py::arg("image_size") = py::none(),
          py::arg("units") = "pixels", py::arg("refine") = "isometric", py::arg("border") = "auto",
          py::arg("border_mode") = "free", py::arg("iterations") = 1000, py::arg("tolerance") = 1e-6, py::arg("snap") = -1.0,
          R"(Maps the disc mesh (V, F) so that every feature lands exactly on its image point, with a certified
injective map (paper §2; `ctmap map` with the same options gives the same UVs, bit for bit).

features: a list of dicts {"name": str, "vertex": int or "point": [x, y, z], "image": [x, y]}; image points in
pixels of an image of image_size=(width, height) (units="pixels", the default) or in UV (units="uv").
Returns a dict: V, F (the cut mesh: the input's vertices first, then inserted ones), UV (one per vertex, OBJ's
convention v up), UV_corners (m x 3 x 2), chart (m), feature_vertex, certificate.
Raises ValueError for bad input (naming the feature), RuntimeError for an internal failure.
The GIL is released while the map is computed.)");
    m.def("certify", &certify_py, py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("feature_vertex") = std::vector<int>{},
          py::arg("feature_uv") = py::none(),
          "The validity certificate of a map with one UV per vertex (exact predicates), as a dict.");
    m.def("map_charts", &map_charts_py, py::arg("V"), py::arg("F"), py::arg("charts"), py::arg("refine") = "isometric",
          py::arg("border_mode") = "free", py::arg("iterations") = 1000,
          R"(Maps a mesh of any topology with several charts (paper §3; `ctmap map` with a charts file):
charts is a list of dicts {"name", "image_size": (w, h), "border": [feature names in order], "features": [...]}
(features as map_texture's, image points in pixels of that chart's image). Faces in no chart are mapped
automatically as one more chart ("rest"). Returns a dict: V, F, UV_corners (m x 3 x 2), chart (m),
chart_names, input_face, occurrences (a dict per feature per chart: name, chart, vertex, uv), certificate.)");
    m.def("bake", &bake_py, py::arg("map"), py::arg("photo"), py::arg("V"), py::arg("F"), py::arg("UV"),
          py::arg("size") = py::none(), py::arg("padding") = 8, py::arg("max_distance") = -1.0, py::arg("transfer") = "auto",
          py::arg("tile") = py::none(),
          R"(Bakes `photo` (H x W x 3 or 4 uint8; a list of them, one per chart, for map_charts' result), mapped by
`map` (the dict map_texture or map_charts returns), into the UV
layout UV of the mesh (V, F): UV n x 2 (per vertex) or m x 3 x 2 (per face corner), OBJ's convention, v up
(`ctmap bake`). Exact when (V, F) is the mesh the map was computed from, else by the closest point of the map
(texels farther than max_distance, default 1% of the bounding box, left empty). size=(width, height), default
the photo's. UVs outside [0, 1] are UDIM tiles: tile=1002 bakes that one (required when there are several).
Returns a dict: texture (height x width x 4 uint8, rows top to bottom, alpha 0 where nothing was
written), covered (height x width bool), exact, not_exact, covered_texels, written_twice, too_far, padded.
Raises ValueError for bad input. The GIL is released while baking.)");
    m.def("write_obj", [](const std::string& path, const Doubles& V, const Ints& F, const Doubles& UV, const std::string& image) {
        write_obj(textured_from(V, F, UV), path, image);
    }, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("image") = "",
          "Writes OBJ + MTL (the MTL names `image`), atomically.");
    m.def("write_glb", [](const std::string& path, const Doubles& V, const Ints& F, const Doubles& UV, const std::string& image) {
        write_glb(textured_from(V, F, UV), path, image);
    }, py::arg("path"), py::arg("V"), py::arg("F"), py::arg("UV"), py::arg("image") = "",
          "Writes a binary glTF with `image` embedded as its texture.");
}
