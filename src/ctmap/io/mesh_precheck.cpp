#include "ctmap/io/mesh_precheck.h"

#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

[[noreturn]] void refuse(std::string_view path, const std::string& problem) {
    throw BadInput(std::string(path), problem);
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

/// A cursor over whitespace-separated tokens.
struct Tokens {
    std::string_view text;
    std::size_t at = 0;
    bool next(std::string_view& tok) {
        while (at < text.size() && is_space(text[at])) ++at;
        if (at >= text.size()) return false;
        const std::size_t start = at;
        while (at < text.size() && !is_space(text[at])) ++at;
        tok = text.substr(start, at - start);
        return true;
    }
    std::size_t left() const { return text.size() - at; }
};

bool as_count(std::string_view t, long long& v) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && end == t.data() + t.size() && v >= 0;
}

/// One PLY property: a scalar, or a list with its count's type and its values' type.
struct PlyProperty {
    bool list = false;
    int count_bytes = 0;
    int value_bytes = 0;
    std::string name;
};

struct PlyElement {
    std::string name;
    long long count = 0;
    std::vector<PlyProperty> properties;
};

int ply_type_bytes(std::string_view t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

/// Reads a binary unsigned or signed integer count of `bytes` bytes.
long long read_count(const unsigned char* p, int bytes, bool little) {
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= std::uint64_t(p[little ? i : bytes - 1 - i]) << (8 * i);
    // Signed types: a value with the top bit set is negative.
    if (v & (std::uint64_t(1) << (8 * bytes - 1))) return -1;
    return (long long)v;
}

}  // namespace

void check_ply_declarations(const std::string_view path, std::string_view bytes) {
    if (bytes.substr(0, 3) != "ply") return;  // not PLY at all: diagnose_mesh_file says what it is
    const std::size_t end = bytes.find("end_header");
    if (end == std::string_view::npos) refuse(path, "not a valid ply file: the header has no 'end_header' line");
    std::size_t data = bytes.find('\n', end);
    data = data == std::string_view::npos ? bytes.size() : data + 1;
    std::vector<PlyElement> elements;
    std::string format;
    int line = 0;
    std::size_t pos = 0;
    while (pos < end) {
        std::size_t eol = bytes.find('\n', pos);
        if (eol == std::string_view::npos || eol > end) eol = end;
        ++line;
        Tokens t{bytes.substr(pos, eol - pos)};
        pos = eol + 1;
        std::string_view kw, a, b, c, d;
        if (!t.next(kw)) continue;
        const std::string at = "not a valid ply file: line " + std::to_string(line) + ": ";
        if (kw == "format" && t.next(a)) format = std::string(a);
        if (kw == "element") {
            PlyElement e;
            if (!t.next(a) || !t.next(b) || !as_count(b, e.count))
                refuse(path, at + "an element needs a name and a non-negative integer count");
            e.name = std::string(a);
            elements.push_back(e);
        } else if (kw == "property") {
            if (elements.empty()) refuse(path, at + "a 'property' line before any 'element' line");
            PlyProperty p;
            if (!t.next(a)) refuse(path, at + "a property needs a type and a name");
            if (a == "list") {
                if (!t.next(b) || !t.next(c) || !t.next(d)) refuse(path, at + "a list property needs two types and a name");
                p.list = true;
                p.count_bytes = ply_type_bytes(b);
                p.value_bytes = ply_type_bytes(c);
                p.name = std::string(d);
                if (p.count_bytes == 0 || p.count_bytes == 8 || p.value_bytes == 0)
                    refuse(path, at + "unknown list types '" + std::string(b) + "' '" + std::string(c) + "'");
            } else {
                p.value_bytes = ply_type_bytes(a);
                if (!t.next(b)) refuse(path, at + "a property needs a type and a name");
                p.name = std::string(b);
                if (p.value_bytes == 0) refuse(path, at + "unknown property type '" + std::string(a) + "'");
            }
            elements.back().properties.push_back(p);
        }
    }
    const std::string_view body = bytes.substr(data);
    if (format == "ascii") {
        Tokens t{body};
        for (const PlyElement& e : elements) {
            if (e.properties.empty()) continue;
            // Each value takes at least two characters ("0 "): the count must fit before reading.
            if ((long double)e.count * e.properties.size() * 2 > (long double)body.size() + 2)
                refuse(path, "not a valid ply file: the file is truncated: the header declares " +
                                 std::to_string(e.count) + " " + e.name + " elements, which cannot fit in its " +
                                 std::to_string(body.size()) + " bytes of data");
            for (long long i = 0; i < e.count; ++i)
                for (const PlyProperty& p : e.properties) {
                    std::string_view tok;
                    if (!t.next(tok)) return;  // truncated: the reader and diagnose_mesh_file say where
                    long long n = 0;
                    if (!p.list) continue;
                    if (!as_count(tok, n)) return;
                    if ((long double)n * 2 > (long double)t.left() + 2)
                        refuse(path, "not a valid ply file: " + e.name + " " + std::to_string(i) + " declares a list of " +
                                         std::to_string(n) + " values, more than the file holds");
                    for (long long k = 0; k < n; ++k)
                        if (!t.next(tok)) return;
                }
        }
        return;
    }
    if (format != "binary_little_endian" && format != "binary_big_endian") return;  // the reader refuses it
    const bool little = format == "binary_little_endian";
    std::size_t at = 0;
    for (const PlyElement& e : elements) {
        long long min_bytes = 0;
        for (const PlyProperty& p : e.properties) min_bytes += p.list ? p.count_bytes : p.value_bytes;
        if ((long double)e.count * min_bytes > (long double)(body.size() - at))
            refuse(path, "not a valid ply file: the file is truncated: the header declares " + std::to_string(e.count) +
                             " " + e.name + " elements (at least " + std::to_string(min_bytes) +
                             " bytes each), but only " + std::to_string(body.size() - at) + " bytes are left");
        bool has_list = false;
        for (const PlyProperty& p : e.properties) has_list |= p.list;
        if (!has_list) {
            at += std::size_t(e.count * min_bytes);
            continue;
        }
        for (long long i = 0; i < e.count; ++i)
            for (const PlyProperty& p : e.properties) {
                if (!p.list) {
                    at += p.value_bytes;
                    continue;
                }
                if (at + p.count_bytes > body.size())
                    refuse(path, "not a valid ply file: the file is truncated in " + e.name + " " + std::to_string(i));
                const long long n = read_count(reinterpret_cast<const unsigned char*>(body.data() + at), p.count_bytes, little);
                at += p.count_bytes;
                if (n < 0 || (long double)n * p.value_bytes > (long double)(body.size() - at))
                    refuse(path, "not a valid ply file: " + e.name + " " + std::to_string(i) + " declares a list of " +
                                     std::to_string(n) + " values, more than the file holds");
                at += std::size_t(n) * p.value_bytes;
            }
        if (at > body.size()) refuse(path, "not a valid ply file: the file is truncated in the " + e.name + " elements");
    }
}

void check_off_face_sizes(const std::string_view path, std::string_view bytes) {
    // The header: a keyword line ending in OFF (counts on it or on the next non-comment line).
    std::size_t pos = 0;
    auto next_line = [&](std::string_view& l) {
        while (pos < bytes.size()) {
            std::size_t eol = bytes.find('\n', pos);
            if (eol == std::string_view::npos) eol = bytes.size();
            l = bytes.substr(pos, eol - pos);
            pos = eol + 1;
            if (const std::size_t c = l.find('#'); c != std::string_view::npos) l = l.substr(0, c);
            Tokens t{l};
            std::string_view first;
            if (t.next(first)) return true;
        }
        return false;
    };
    std::string_view l, kw, a, b;
    if (!next_line(l)) return;
    Tokens head{l};
    if (!head.next(kw) || kw.size() < 3 || kw.substr(kw.size() - 3) != "OFF") return;
    if (head.next(a) && a == "BINARY") return;  // check_off_counts bounds the binary form
    long long nv = 0, nf = 0;
    if (a.empty()) {
        if (!next_line(l)) return;
        head = Tokens{l};
        if (!head.next(a)) return;
    }
    if (!as_count(a, nv) || !head.next(b) || !as_count(b, nf)) return;
    for (long long v = 0; v < nv; ++v)
        if (!next_line(l)) return;
    for (long long f = 0; f < nf; ++f) {
        if (!next_line(l)) return;
        Tokens t{l};
        std::string_view n;
        long long corners = 0;
        if (!t.next(n) || !as_count(n, corners)) return;  // diagnose_mesh_file names the line
        if ((long double)corners * 2 > (long double)(bytes.size() - std::min(pos, bytes.size())) + l.size())
            refuse(path, "not a valid off file: face " + std::to_string(f) + " declares " + std::to_string(corners) +
                             " corners, more than the file holds");
    }
}

}  // namespace ctmap
