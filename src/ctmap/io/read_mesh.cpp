#include "ctmap/io/read_mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <tuple>

#include "ctmap/errors.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/mesh_diagnosis.h"
#include "ctmap/io/triangulate_polygon.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

/// Checks that `path` is a readable, non-empty file with a mesh extension; returns the extension.
std::string check_mesh_file(const std::string& path) {
    check_input_file(path, "mesh file");
    const std::string ext = lower_extension(path);
    if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl")
        throw BadInput(path, "unknown mesh format '" + ext + "' (use .off, .obj, .ply or .stl)");
    return ext;
}

/// CGAL's stream readers on the file's bytes, held in memory: a UTF-8 byte-order mark (which
/// Windows editors write) is skipped, so the first line is not lost; binary modes as CGAL's own
/// file readers set them.
bool read_soup_from_bytes(const std::string& bytes, const std::string& ext, std::vector<Point>& points,
                          std::vector<std::vector<std::size_t>>& polygons) {
    const std::string text = bytes.substr(utf8_bom_length(bytes));
    const auto np = CGAL::parameters::verbose(false);
    std::istringstream is(text, std::ios::in | std::ios::binary);
    if (ext == ".off") return CGAL::IO::read_OFF(is, points, polygons, np);
    if (ext == ".obj") return CGAL::IO::read_OBJ(is, points, polygons, np);
    if (ext == ".ply") {
        CGAL::IO::set_mode(is, CGAL::IO::BINARY);
        return CGAL::IO::read_PLY(is, points, polygons, np);
    }
    CGAL::IO::set_mode(is, CGAL::IO::BINARY);  // STL: binary first, then ASCII, as CGAL's read_STL
    if (CGAL::IO::read_STL(is, points, polygons, np)) return true;
    points.clear();
    polygons.clear();
    std::istringstream ascii(text);
    CGAL::IO::set_mode(ascii, CGAL::IO::ASCII);
    return CGAL::IO::read_STL(ascii, points, polygons, np);
}

/// Reads the polygon soup with CGAL; when CGAL fails, says why (mesh_diagnosis.h).
void read_soup(const std::string& path, const std::string& ext, std::vector<Point>& points,
               std::vector<std::vector<std::size_t>>& polygons) {
    const std::string bytes = read_input_file(path, "mesh file");
    check_before_reading(path, ext, bytes);  // what CGAL would trust blindly (mesh_diagnosis.h)
    const std::string what = "not a valid " + ext.substr(1) + " file: ";
    bool ok = false;
    try {
        ok = read_soup_from_bytes(bytes, ext, points, polygons);
    } catch (const std::exception& e) {
        const std::string why = diagnose_mesh_file(path, ext);
        throw BadInput(path, what + (why.empty() ? std::string("the reader failed (") + e.what() + ")" : why));
    }
    if (!ok) {
        const std::string why = diagnose_mesh_file(path, ext);
        throw BadInput(path, what + (why.empty() ? "the reader stopped on malformed data" : why));
    }
    if (points.empty()) throw BadInput(path, "the mesh has no vertices");
    if (polygons.empty()) throw BadInput(path, "the mesh has no faces");
}

/// Checks one polygon of the soup: at least 3 corners, every index in range.
void check_polygon(const std::string& path, std::size_t f, const std::vector<std::size_t>& poly, std::size_t num_points) {
    if (poly.size() < 3)
        throw BadInput(path, "face " + std::to_string(f) + " has " + std::to_string(poly.size()) +
                                 " corners; a face needs at least 3");
    for (std::size_t v : poly)
        if (v >= num_points)
            throw BadInput(path, "face " + std::to_string(f) + " uses vertex " + std::to_string(v) +
                                     ", which is out of range (the file has " + std::to_string(num_points) +
                                     " vertices)");
}

}  // namespace

TriMesh read_mesh(const std::string& path) {
    const std::string ext = check_mesh_file(path);
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    read_soup(path, ext, points, polygons);

    TriMesh mesh;
    mesh.positions.reserve(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const Point& p = points[i];
        if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z()))
            throw BadInput(path, "vertex " + std::to_string(i) + " has a non-finite coordinate (NaN or infinity)");
        mesh.positions.emplace_back(p.x(), p.y(), p.z());
    }
    mesh.faces.reserve(polygons.size());
    for (std::size_t f = 0; f < polygons.size(); ++f) {
        check_polygon(path, f, polygons[f], points.size());
        triangulate_polygon(path, f, polygons[f], mesh.positions, mesh.faces);
    }
    return mesh;
}

}  // namespace ctmap
