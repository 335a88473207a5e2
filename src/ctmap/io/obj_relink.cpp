#include "ctmap/io/obj_relink.h"

#include <string_view>

namespace ctmap {
namespace {
/// Whether `line` (its leading blanks skipped) starts with the keyword `kw` and a blank or its end.
bool keyword(std::string_view line, std::string_view kw) {
    const std::size_t s = line.find_first_not_of(" \t");
    if (s == std::string_view::npos) return false;
    line.remove_prefix(s);
    if (line.substr(0, kw.size()) != kw) return false;
    return line.size() == kw.size() || line[kw.size()] == ' ' || line[kw.size()] == '\t' || line[kw.size()] == '\r';
}
}  // namespace

std::string relink_obj(const std::string& obj, const std::string& mtl_name, const std::string& material) {
    const std::string eol = obj.find("\r\n") != std::string::npos ? "\r\n" : "\n";
    std::string out = "mtllib " + mtl_name + eol;
    out.reserve(obj.size() + 64);
    bool used = false;
    std::size_t start = 0;
    while (start < obj.size()) {
        std::size_t end = obj.find('\n', start);
        end = end == std::string::npos ? obj.size() : end + 1;  // the line with its ending
        const std::string_view line(obj.data() + start, end - start);
        if (keyword(line, "mtllib")) {
            // left out: the new one is first
        } else if (keyword(line, "usemtl")) {
            out += "usemtl " + material + eol;
            used = true;
        } else {
            if (!used && keyword(line, "f")) {
                out += "usemtl " + material + eol;
                used = true;
            }
            out += line;
        }
        start = end;
    }
    return out;
}

}  // namespace ctmap
