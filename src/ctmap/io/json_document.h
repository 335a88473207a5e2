#pragma once
/// \file json_document.h
/// Parsing a small JSON input file (features, pairs) safely: an empty text, a nesting deep enough
/// to overflow the parser's recursion (issue 17), a syntax error and a number no double holds are
/// all `BadInput` naming the file.
#include <nlohmann/json.hpp>
#include <string>

namespace ctmap {

/// Arrays and objects nest at most this deep in ctmap's JSON inputs (DESIGN §4 needs 4 or 5).
constexpr int kMaxJsonNesting = 64;

/// Parses `text` (the file `path`, a `what` such as "features file" for the messages).
/// \throw BadInput naming `path`: empty text, nesting deeper than kMaxJsonNesting (checked before
///        the parser recurses), invalid JSON, a number out of a double's range.
nlohmann::json parse_json_document(const std::string& text, const std::string& path, const std::string& what);

/// `j` as an array of `n` numbers into `out`; false if it is not one.
bool read_number_array(const nlohmann::json& j, std::size_t n, double* out);

/// True if the `n` values are all finite.
bool all_finite(const double* v, std::size_t n);

}  // namespace ctmap
