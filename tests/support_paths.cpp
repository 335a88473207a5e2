#include "support_paths.h"

namespace ctmap_test {

const char* ctmap_binary() { return CTMAP_BINARY; }
const char* source_dir() { return CTMAP_TESTS_SOURCE_DIR; }

}  // namespace ctmap_test
