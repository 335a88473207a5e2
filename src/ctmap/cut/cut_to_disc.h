#pragma once
/// \file cut_to_disc.h
/// A connected surface of any genus and any number of border loops cut open into one disc
/// (issue 13: the faces in no chart are mapped automatically). The cut graph is the classic one:
/// the edges a dual spanning tree of the faces does not cross, with dangling trees pruned away
/// (what remains joins the border loops and runs through every handle), and the surface is cut
/// along it, each vertex on the cut split into one copy per wedge of faces between cut edges.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// The surface cut open.
struct DiscCut {
    TriMesh disc;                ///< the faces in the input's order, on split vertices
    std::vector<int> original;   ///< per vertex of `disc`, its vertex of the input
    int cut_edges = 0;           ///< interior edges of the input that the cut opened
};

/// Cuts `mesh` into a disc. A disc comes back as it is (no edge cut).
/// A closed sphere has no such cut graph: it is opened by a slit of two edges.
/// \pre `mesh` is a connected, consistently oriented manifold.
/// \throw BadInput for several components; InternalError if the result is not a disc (a bug).
DiscCut cut_to_disc(const TriMesh& mesh);

}  // namespace ctmap
