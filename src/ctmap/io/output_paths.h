#pragma once
/// \file output_paths.h
/// Checks on a command's output paths, made before any work (issue 17): an output is never an
/// input or another output, and every output can be created, so a run either writes everything
/// or fails at once with exit 2, never after minutes of computation and never over an input.
#include <string>
#include <vector>

namespace ctmap {

/// One path a command reads or writes, with what it is (for messages: "the mesh", "--glb").
struct NamedPath {
    std::string path;
    std::string role;
};

/// Whether `a` and `b` name the same file: the same path after resolving `.`, `..` and symbolic
/// links (of the folders too, for files that do not exist yet), or two hard links of one file.
bool same_file(const std::string& a, const std::string& b);

/// Checks every output before a command does any work:
/// - no output is the same file as an input or as another output (`same_file`);
/// - each output names a file, not a folder; its folder exists; a new file can be created in it
///   (a probe file is created and removed, so read-only folders and file systems are caught).
/// Empty paths in either list are skipped.
/// \throw BadInput naming the output and the reason.
void check_outputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace ctmap
