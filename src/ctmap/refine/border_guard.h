#pragma once
/// \file border_guard.h
/// The free border's guard for the distortion optimiser (beyond paper §2.4): a trial map is
/// accepted only if its UV border is still a simple loop (exact predicates on every pair of
/// border edges after a box-intersection filter, the certificate's own test) and stays inside
/// the allowed rectangle (the image). With every triangle positively oriented, a simple border
/// makes the map of a disc one-to-one.
#include <array>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Checks trial maps of one disc mesh.
class BorderGuard {
public:
    /// \param loop the mesh's border loop (border_loop.h); empty for no border check.
    /// \param lo, hi the rectangle every border vertex must stay in (inclusive).
    BorderGuard(const std::vector<int>& loop, const Vec2& lo, const Vec2& hi);

    /// Whether the border of `uv` is simple and inside the rectangle. O(B log B) for B border edges.
    bool ok(const std::vector<Vec2>& uv) const;
    /// Whether every border vertex of `uv` lies in the rectangle. O(B).
    bool inside(const std::vector<Vec2>& uv) const;

    /// The vertices of the border edges that cross or touch another where they must not.
    std::vector<int> crossing_vertices(const std::vector<Vec2>& uv) const;

    const std::vector<int>& loop() const { return loop_; }

private:
    std::vector<int> loop_;
    std::vector<std::array<int, 2>> edges_;
    Vec2 lo_, hi_;
};

}  // namespace ctmap
