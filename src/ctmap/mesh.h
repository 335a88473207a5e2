#pragma once
/// \file mesh.h
/// Plain mesh types passed between the pipeline's stages. No CGAL here: CGAL stays inside the few
/// translation units that need it (DESIGN §5).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace ctmap {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Tri = std::array<int, 3>;

/// A triangle mesh: positions and counter-clockwise index triples, 0-based, in input order.
struct TriMesh {
    std::vector<Vec3> positions;
    std::vector<Tri> faces;

    int num_vertices() const { return static_cast<int>(positions.size()); }
    int num_faces() const { return static_cast<int>(faces.size()); }
};

/// A triangle mesh with texture coordinates per face corner (DESIGN §7: several charts and seams
/// come later, so UVs are never stored per vertex). `uv_faces[f][k]` indexes `uvs` for corner k of
/// face f; `chart[f]` is the chart id of face f (0 when there is one chart).
struct TexturedMesh {
    TriMesh mesh;
    std::vector<Vec2> uvs;
    std::vector<Tri> uv_faces;
    std::vector<int> chart;
    /// Optional: per face, the patch (image triangle) it was mapped into; written to OBJ as
    /// `g patch_<id>` groups so that `ctmap render --mode paths` can draw the cut from the file.
    /// Empty when unknown.
    std::vector<int> patch;
    /// Optional: per face, the face of the input mesh it lies in (input_faces.h), written to OBJ
    /// as `#ctmap_input_face` comment lines, so that `ctmap bake` can carry the map onto the
    /// input exactly. Empty when unknown.
    std::vector<int> input_face;

    /// A textured mesh whose UVs are per vertex (one chart): uv_faces = faces.
    static TexturedMesh with_vertex_uvs(TriMesh m, std::vector<Vec2> vertex_uvs) {
        TexturedMesh t;
        t.uv_faces = m.faces;
        t.chart.assign(m.faces.size(), 0);
        t.mesh = std::move(m);
        t.uvs = std::move(vertex_uvs);
        return t;
    }
};

/// What a chart is textured with in OBJ and GLB output (issue 13): material `name` (letters,
/// digits, '_' and '-' only) with the image `image` (a path; empty: untextured).
struct ChartMaterial {
    std::string name;
    std::string image;
};

}  // namespace ctmap
