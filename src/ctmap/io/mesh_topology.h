#pragma once
/// \file mesh_topology.h
/// What kind of surface a triangle soup is: the facts `ctmap info` prints and the checks every
/// later stage needs (the method works on a disc, paper §2.2).
#include <string>

#include "ctmap/mesh.h"

namespace ctmap {

/// Topology of a triangle mesh. Counts refer to the mesh as given (no repair).
struct MeshTopology {
    int vertices = 0;
    int faces = 0;
    int edges = 0;
    int components = 0;             ///< connected components of faces (sharing vertices)
    int border_loops = 0;           ///< connected components of the border-edge graph
    int border_edges = 0;
    int euler = 0;                  ///< V - E + F
    int non_manifold_vertices = 0;  ///< vertices whose incident faces form more than one fan
    int non_manifold_edges = 0;     ///< edges with more than two incident faces
    int inconsistent_edges = 0;     ///< interior edges whose two faces are oriented oppositely
    int degenerate_faces = 0;       ///< repeated corner or exactly collinear corners
    int duplicated_vertices = 0;    ///< vertices at exactly the position of an earlier vertex
    int isolated_vertices = 0;      ///< vertices used by no face
    bool is_manifold = false;       ///< no non-manifold vertex or edge, consistently oriented
    bool is_disc = false;           ///< manifold, one component, one border loop, Euler 1
    bool is_closed = false;         ///< manifold, no border edge
};

/// Computes the topology report of `mesh`.
/// \pre every face index is in range (as `read_mesh` guarantees).
MeshTopology compute_topology(const TriMesh& mesh);

/// What a "not a disc" message advises: `charts` where the command accepts a features file with
/// charts (`map`, `validate`), `cut_open` where it takes one chart only (`serve`, `morph`, Python).
enum class NotDiscAdvice { charts, cut_open };

/// Checks that `mesh` is a topological disc with no degenerate face, as the constrained map needs.
/// \throw TopologyError naming `file` and every problem found (and what to do about it, per `advice`).
void require_disc(const MeshTopology& topo, const std::string& file, NotDiscAdvice advice = NotDiscAdvice::charts);

/// Checks that `mesh` is a consistently oriented manifold with no degenerate face or isolated
/// vertex, of any genus and with any number of border loops (several charts, issue 13).
/// \throw TopologyError naming `file` and every problem found.
void require_manifold(const MeshTopology& topo, const std::string& file);

/// The report as JSON text with the keys of DESIGN/issue 2 (`vertices`, `faces`, ...).
std::string topology_to_json(const MeshTopology& topo);

}  // namespace ctmap
