#include "ctmap/io/json_document.h"

#include <cmath>

#include "ctmap/errors.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

/// Refuses documents nested deeper than kMaxJsonNesting, counted outside strings, before the JSON
/// parser (which recurses once per level, and overflows the stack past ~10,000) sees them.
void check_nesting(const std::string& text, const std::string& path, const std::string& what) {
    int depth = 0;
    bool in_string = false;
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') ++line;
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
            continue;
        }
        if (c == '"') in_string = true;
        else if (c == '[' || c == '{') {
            if (++depth > kMaxJsonNesting)
                throw BadInput(path, "line " + std::to_string(line) + ": arrays and objects nested more than " +
                                         std::to_string(kMaxJsonNesting) + " deep: not a " + what);
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
}

}  // namespace

nlohmann::json parse_json_document(const std::string& text, const std::string& path, const std::string& what) {
    if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw BadInput(path, "the " + what + " is empty");
    check_nesting(text, path, what);  // before the parser recurses into it
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        throw BadInput(path, "not valid JSON: " + printable(e.what(), 200));
    } catch (const nlohmann::json::out_of_range& e) {  // a number such as 1e999 that no double holds
        throw BadInput(path, "a number is out of range (too large for a double): " + printable(e.what(), 200));
    } catch (const nlohmann::json::exception& e) {
        throw BadInput(path, "not valid JSON: " + printable(e.what(), 200));
    }
}

bool read_number_array(const nlohmann::json& j, std::size_t n, double* out) {
    if (!j.is_array() || j.size() != n) return false;
    for (std::size_t i = 0; i < n; ++i) {
        if (!j[i].is_number()) return false;
        out[i] = j[i].get<double>();
    }
    return true;
}

bool all_finite(const double* v, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}

}  // namespace ctmap
