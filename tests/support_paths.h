#pragma once
/// \file support_paths.h
/// Where the tests find the `ctmap` program and the source tree. One translation unit
/// (support_paths.cpp) holds the paths, so that no other test file's command line differs
/// between two checkouts (ccache shares them).

namespace ctmap_test {

/// The `ctmap` program of this build.
const char* ctmap_binary();
/// The source tree (fuzz/regressions, the shipped example).
const char* source_dir();

}  // namespace ctmap_test
