#include "support_paths.h"

#include <cstdlib>

namespace ctmap_test {

// CTMAP_TEST_BINARY runs the CLI tests against another build of the program (a copy kept for a
// long sweep while the tree is rebuilt).
const char* ctmap_binary() {
    const char* other = std::getenv("CTMAP_TEST_BINARY");
    return other && *other ? other : CTMAP_BINARY;
}
const char* source_dir() { return CTMAP_TESTS_SOURCE_DIR; }

}  // namespace ctmap_test
