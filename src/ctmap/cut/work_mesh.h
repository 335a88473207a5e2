#pragma once
/// \file work_mesh.h
/// The mesh the cut refines: triangles that only ever get split (never flipped or moved), each
/// remembering the input face it lies in, with the adjacency the path search needs.
#include <array>
#include <cstdint>
#include <vector>

#include "ctmap/edge_key.h"
#include "ctmap/mesh.h"

namespace ctmap {


/// A refinable triangle mesh with its adjacency.
struct WorkMesh {
    std::vector<Vec3> positions;
    std::vector<Tri> faces;
    std::vector<int> origin;  ///< input face each face lies in
    /// Where each vertex lies on the input surface: an input vertex v is {v, v}, a vertex inside
    /// the input edge {a, b} is {a, b} (a < b), a vertex inside an input face {-1, -1}.
    std::vector<std::array<int, 2>> site;
    std::vector<Tri> input_faces;  ///< the input's faces (`origin` indexes them)

    // Adjacency, valid after rebuild().
    std::vector<std::uint64_t> edges;                    ///< edge keys, index = edge id
    std::vector<std::array<int, 2>> edge_faces;          ///< per edge: its faces (-1 when on the border)
    std::vector<std::vector<int>> vertex_faces;          ///< per vertex: incident faces
    std::vector<std::array<int, 3>> face_edges;          ///< per face: edge ids of (t[k], t[k+1]), k = 0..2

    explicit WorkMesh(const TriMesh& m);
    /// The site of a point inside the edge {x, y}: the input edge both lie on, or {-1, -1} when
    /// the edge runs inside an input face. (Two corners of an input face joined by an edge are
    /// joined by a side of it: inside a triangle, nothing else joins two corners.)
    std::array<int, 2> edge_site(int x, int y) const {
        const auto sx = site[x], sy = site[y];
        const bool vx = sx[0] >= 0 && sx[0] == sx[1], vy = sy[0] >= 0 && sy[0] == sy[1];
        if (vx && vy) return {std::min(sx[0], sy[0]), std::max(sx[0], sy[0])};
        if (vx && sy[0] >= 0) return sy[0] == sx[0] || sy[1] == sx[0] ? sy : std::array<int, 2>{-1, -1};
        if (vy && sx[0] >= 0) return sx[0] == sy[0] || sx[1] == sy[0] ? sx : std::array<int, 2>{-1, -1};
        if (sx[0] >= 0 && sx == sy) return sx;
        return {-1, -1};
    }
    void rebuild();
    int num_vertices() const { return int(positions.size()); }
    /// The live edge {a, b}, or -1. Looked up through a's faces rather than a hash map of edge
    /// keys: building that map was a tenth of the cut's time on a million triangles, and a
    /// vertex has few faces.
    int find_edge(int a, int b) const {
        for (int f : vertex_faces[a]) {
            const int k = corner_of(f, a);
            if (faces[f][(k + 1) % 3] == b) return face_edges[f][k];
            if (faces[f][(k + 2) % 3] == b) return face_edges[f][(k + 2) % 3];
        }
        return -1;
    }
    /// The corner of face f at vertex v. \pre v is a corner of f.
    int corner_of(int f, int v) const { return faces[f][0] == v ? 0 : faces[f][1] == v ? 1 : 2; }
    /// A border edge has one face. Edges split by an insertion stay in `edges` with no face at
    /// all (ids are never reused, so ids held elsewhere stay meaningful); they are neither border
    /// nor interior and `find_edge` no longer finds them.
    bool is_border_edge(int e) const { return edge_faces[e][0] >= 0 && edge_faces[e][1] < 0; }
    bool is_live_edge(int e) const { return edge_faces[e][0] >= 0; }

    /// Replaces the faces `removed` by `added` (with their input faces `added_origin`) and updates
    /// the adjacency locally, in time proportional to the faces changed: the cut inserts hundreds
    /// of paths, and rebuilding the whole adjacency after each was the cut's main cost on large
    /// meshes. Added faces take the removed faces' ids first, then new ids at the end; with fewer
    /// faces added than removed, the last faces move into the ids left over.
    /// \pre positions holds every vertex of `added`; the result is a manifold mesh.
    /// \throw InternalError if an edge would get a third face.
    void replace_faces(const std::vector<int>& removed, const std::vector<Tri>& added, const std::vector<int>& added_origin);

    /// Faces around `v` in counter-clockwise order, each with the edge it starts from: for face
    /// (v, x, y) the fan goes from edge (v, x) to edge (v, y). A border vertex's fan starts at
    /// its outgoing border edge. \pre the mesh is a manifold, consistently oriented disc.
    struct FanEntry {
        int face, from, to;  ///< face (v, from, to)
    };
    std::vector<FanEntry> fan(int v) const;

    /// The border as one loop of vertices in the faces' orientation (interior on the left).
    std::vector<int> border_loop() const;
};

}  // namespace ctmap
