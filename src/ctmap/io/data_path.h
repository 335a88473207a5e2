#pragma once
/// \file data_path.h
/// Where the example meshes and images are: `$CTMAP_DATA`, else the project's own `data/`
/// (features files), else `../shared/data` beside the project, else the cache `.cache/data` that
/// `scripts/fetch_data.sh` fills from Debian's packages.
#include <string>
#include <vector>

namespace ctmap {

/// The folders searched for data, in order (only those that exist).
std::vector<std::string> data_dirs();

/// The first existing `<dir>/<relative>` over data_dirs().
/// \throw BadInput listing the folders searched if the file is nowhere.
std::string find_data_file(const std::string& relative);

}  // namespace ctmap
