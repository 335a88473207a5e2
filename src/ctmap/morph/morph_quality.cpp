#include "ctmap/morph/morph_quality.h"

#include <algorithm>

#include <Eigen/Geometry>

#include "ctmap/morph/surface_distance.h"

namespace ctmap {

MorphQuality measure_morph(const MorphResult& m, const TriMesh& target) {
    MorphQuality q;
    const TriMesh& t = m.target_map.cut.mesh;
    for (std::size_t i = 0; i < m.pair_vertex.size(); ++i)
        q.pair_error = std::max(q.pair_error, (m.common.target_position[m.pair_vertex[i]] -
                                               t.positions[m.target_pair_vertex[i]]).norm());
    TriMesh source = m.source_map.cut.mesh;  // where the common mesh's weight-0 shape lies: the aligned source
    const Eigen::Affine3d align(m.alignment);
    for (Vec3& p : source.positions) p = align * p;
    const SurfaceDistance to_target(t), to_source(source);
    for (std::size_t v = 0; v < m.common.mesh.positions.size(); ++v) {
        q.target_off = std::max(q.target_off, to_target.distance(m.common.target_position[v]));
        q.source_off = std::max(q.source_off, to_source.distance(m.common.mesh.positions[v]));
    }
    TriMesh morphed = m.common.mesh;
    morphed.positions = m.common.target_position;
    q.hausdorff = hausdorff_from(target, morphed);
    q.target_mean_edge = mean_edge_length(target);
    Eigen::AlignedBox3d box;
    for (const Vec3& p : target.positions) box.extend(p);
    q.diagonal = box.diagonal().norm();
    return q;
}

}  // namespace ctmap
