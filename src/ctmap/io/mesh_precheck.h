#pragma once
/// \file mesh_precheck.h
/// Checks on a mesh file's own declarations, made before CGAL's readers see it (issue 17). The
/// readers allocate what a header or a face claims (an element count, a face's corner count)
/// before reading it, and CGAL's PLY reader dereferences a null element on a `property` line
/// that comes before any `element`. Every count is checked here against the file's size.
#include <string_view>

namespace ctmap {

/// PLY: the header ends (`end_header`), every `property` follows an `element`, every count is a
/// non-negative integer, and the elements it declares fit in the bytes after the header (at
/// least 2 characters per value in ASCII, the type's size in binary); in ASCII files every list
/// count is at most the number of values left; in binary files every list count fits in the file.
/// \throw BadInput naming `path` and the line or element.
void check_ply_declarations(const std::string_view path, std::string_view bytes);

/// The parts of an OFF keyword [ST][C][N][4]OFF. `known` is false when anything else precedes
/// "OFF". \pre `keyword` ends with "OFF".
struct OffKeyword {
    bool textures = false, colours = false, normals = false, homogeneous = false, known = true;
};
OffKeyword parse_off_keyword(std::string_view keyword);

/// OFF (text, [ST][C][N][4]OFF): every vertex and face line as CGAL's scanner will read it: only
/// finite numbers; enough numbers for the header's coordinates, normals and texture coordinates;
/// a face's corner count an integer of at least 3 that fits in the file, its indices integers in
/// range; colours of 0, 1, 3 or 4 values in range. BINARY OFF is bounded by check_off_counts.
/// \throw BadInput naming `path` and the face.
void check_off_face_sizes(const std::string_view path, std::string_view bytes);

}  // namespace ctmap
