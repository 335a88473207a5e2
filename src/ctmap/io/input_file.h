#pragma once
/// \file input_file.h
/// The checks every reader makes on its file before opening it (issue 17): it exists, it is a
/// regular file (a FIFO, a device or a socket would block `open` or never end), and it is not
/// empty; and the whole file read into memory, so each reader parses bytes it already holds.
#include <string>

namespace ctmap {

/// Checks that `path` names a readable, non-empty regular file. `what` names the kind of file
/// in messages ("mesh", "image", "features file", "OBJ file").
/// \throw BadInput naming `path`: no such file, a folder, not a regular file, empty, unreadable.
void check_input_file(const std::string& path, const std::string& what);

/// The bytes of `path` (after `check_input_file`).
/// \throw BadInput as check_input_file, or if the file cannot be read whole.
std::string read_input_file(const std::string& path, const std::string& what);

/// The length of a UTF-8 byte-order mark at the start of `text` (3), or 0.
std::size_t utf8_bom_length(const std::string& text);

}  // namespace ctmap
