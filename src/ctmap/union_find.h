#pragma once
/// \file union_find.h
/// Disjoint sets with path halving: the mesh's components (io/mesh_topology) and the corners that
/// stay one vertex when a surface is cut open (cut/cut_to_disc).
#include <numeric>
#include <vector>

namespace ctmap {

struct UnionFind {
    std::vector<int> parent;
    explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
    int find(int a) {
        while (parent[a] != a) a = parent[a] = parent[parent[a]];
        return a;
    }
    void unite(int a, int b) { parent[find(a)] = find(b); }
};

}  // namespace ctmap
