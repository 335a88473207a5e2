#pragma once
/// \file glb_io.h
/// Binary glTF output (tinygltf) with the texture embedded: one file three.js and Blender open.
#include <string>
#include <vector>

#include "ctmap/io/atomic_file.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Writes `mesh` as a binary glTF to `path`, with the PNG or JPEG file `image` embedded as the
/// base-colour texture (untextured when `image` is empty). glTF stores one UV per vertex, so a
/// vertex is split where its corners carry different UVs: glTF vertex i is input vertex i (the
/// input order is kept, DESIGN §3) and the extra copies follow. glTF's v runs downwards, so v is
/// flipped (DESIGN §3). Positions and UVs are stored as 32-bit floats, as glTF requires.
/// The file is registered in `outputs` and appears only when the caller commits it.
/// \throw BadInput if `image` cannot be read or is not a PNG/JPEG, or if a position does not fit
///        in a 32-bit float; InternalError if the file cannot be written.
void write_glb(const TexturedMesh& mesh, const std::string& path, const std::string& image, OutputSet& outputs);

/// Same with one material per chart (issue 13): one glTF primitive per chart on shared vertex
/// attributes, chart c (TexturedMesh::chart) with `materials[c]` and its image embedded (charts
/// sharing an image share one copy). \throw BadInput if a chart id does not index `materials`, as write_glb.
void write_glb(const TexturedMesh& mesh, const std::string& path, const std::vector<ChartMaterial>& materials,
               OutputSet& outputs);

/// Same, committed at once.
void write_glb(const TexturedMesh& mesh, const std::string& path, const std::string& image = "");

/// Writes a morph as a binary glTF: the mesh in its `base` shape with `target` (one position per
/// vertex) as its one glTF morph target (POSITION and NORMAL displacements, named "target" in
/// `extras.targetNames`), mesh weight 0, and an animation "morph" of the weight 0 -> 1 -> 0 over
/// 2 `seconds` (three.js's AnimationMixer and Blender play it). Registered in `outputs`.
/// \throw BadInput if a coordinate does not fit a 32-bit float; InternalError if it cannot be written.
void write_morph_glb(const TriMesh& base, const std::vector<Vec3>& target, const std::string& path, OutputSet& outputs,
                     double seconds = 2.0);

/// The base-colour texture embedded in a glTF file, as stored: the encoded PNG or JPEG bytes.
struct GlbTexture {
    std::string mime_type;             ///< "image/png" or "image/jpeg"; empty if there is no texture
    std::vector<unsigned char> bytes;  ///< the image file's bytes, as embedded
};

/// Reads back the first primitive of a glTF/GLB file: positions, indices and TEXCOORD_0 (in OBJ's
/// convention, v flipped back), one UV per corner. Meant for tests and `ctmap check`.
/// The flip back is one double subtraction, 1 - stored: it gives back the stored float exactly
/// when that is 0 or at least 2^-30 (u, and v not within 1e-9 of 1), and within 2^-54 otherwise.
/// If `texture` is given, it receives the first material's base-colour texture when that is
/// embedded in the file's buffer (and is cleared otherwise).
/// \throw BadInput naming the file if it cannot be loaded, has no indexed triangle primitive, or
///        an accessor or index points outside its buffer.
/// `uv_attribute` names the UV set read (another than TEXCOORD_0: `ctmap bake --onto-uv`); a
/// primitive without it reads as one without UVs.
TexturedMesh read_glb(const std::string& path, GlbTexture* texture = nullptr,
                      const std::string& uv_attribute = "TEXCOORD_0");

}  // namespace ctmap
