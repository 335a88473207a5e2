#include "ctmap/io/mesh_precheck.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ctmap/errors.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

[[noreturn]] void refuse(std::string_view path, const std::string& problem) {
    throw BadInput(std::string(path), problem);
}

/// A count read as a double, in words: digits while it fits a long long, else scientific.
std::string short_count(double n) {
    if (n < 9e18) return std::to_string((long long)n);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", n);
    return buf;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

/// A cursor over whitespace-separated tokens.
struct TokenReader {
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

struct PlyHeaderElement {
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
    // Not PLY at all: diagnose_mesh_file says what it is. CGAL's reader skips leading white space
    // (a vertical tab before "ply" is still PLY to it), so the check does too.
    std::size_t lead = 0;
    while (lead < bytes.size() && is_space(bytes[lead])) ++lead;
    if (bytes.substr(lead, 3) != "ply") return;
    // The header ends at the first line whose word is `end_header` (not any "end_header" inside
    // a word: "elemend_header" ends nothing, and CGAL's reader reads on past it).
    std::size_t end = std::string_view::npos;
    for (std::size_t p = 0; p < bytes.size();) {
        std::size_t eol = bytes.find('\n', p);
        if (eol == std::string_view::npos) eol = bytes.size();
        TokenReader t{bytes.substr(p, eol - p)};
        std::string_view first;
        if (t.next(first) && first == "end_header") {
            end = p;
            break;
        }
        p = eol + 1;
    }
    if (end == std::string_view::npos) refuse(path, "not a valid ply file: the header has no 'end_header' line");
    std::size_t data = bytes.find('\n', end);
    data = data == std::string_view::npos ? bytes.size() : data + 1;
    std::vector<PlyHeaderElement> elements;
    std::string format;
    int line = 0;
    std::size_t pos = 0;
    while (pos < end) {
        std::size_t eol = bytes.find('\n', pos);
        if (eol == std::string_view::npos || eol > end) eol = end;
        ++line;
        TokenReader t{bytes.substr(pos, eol - pos)};
        pos = eol + 1;
        std::string_view kw, a, b, c, d;
        if (!t.next(kw)) continue;
        const std::string at = "not a valid ply file: line " + std::to_string(line) + ": ";
        if (kw == "format" && t.next(a)) format = std::string(a);
        if (kw == "element") {
            PlyHeaderElement e;
            if (!t.next(a) || !t.next(b) || !as_count(b, e.count))
                refuse(path, at + "an element needs a name and a non-negative integer count");
            e.name = printable(a);  // names are only quoted in messages
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
                p.name = printable(d);
                if (p.count_bytes == 0 || p.count_bytes == 8 || p.value_bytes == 0)
                    refuse(path, at + "unknown list types '" + printable(b) + "' '" + printable(c) + "'");
            } else {
                p.value_bytes = ply_type_bytes(a);
                if (!t.next(b)) refuse(path, at + "a property needs a type and a name");
                p.name = printable(b);
                if (p.value_bytes == 0) refuse(path, at + "unknown property type '" + printable(a) + "'");
            }
            elements.back().properties.push_back(p);
        }
    }
    const std::string_view body = bytes.substr(data);
    // An element without properties takes no bytes, so its count is not bounded by the file: CGAL
    // loops over it reading nothing (a fuzz input declared 3.3e16 of them: a hang in the sanitizer
    // build). No mesh file needs more of them than it has bytes.
    for (const PlyHeaderElement& e : elements)
        if (e.properties.empty() && (long double)e.count > (long double)bytes.size())
            refuse(path, "not a valid ply file: the header declares " + std::to_string(e.count) + " '" + e.name +
                             "' elements with no properties, more than the file's " + std::to_string(bytes.size()) +
                             " bytes (a corrupt header)");
    if (format == "ascii") {
        TokenReader t{body};
        for (const PlyHeaderElement& e : elements) {
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
                    // CGAL reads the count as its integer type: "-1.3" became 4294967295 values
                    // and 2 GB allocated (a fuzz input). A count is a non-negative integer.
                    if (!as_count(tok, n))
                        refuse(path, "not a valid ply file: " + e.name + " " + std::to_string(i) +
                                         ": the count of its list '" + p.name + "' is '" +
                                         printable(tok) + "', not a non-negative integer");
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
    for (const PlyHeaderElement& e : elements) {
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

OffKeyword parse_off_keyword(std::string_view keyword) {
    OffKeyword k;
    std::string_view prefix = keyword.substr(0, keyword.size() - 3);
    k.textures = prefix.substr(0, 2) == "ST";
    if (k.textures) prefix.remove_prefix(2);
    k.colours = !prefix.empty() && prefix[0] == 'C';
    if (k.colours) prefix.remove_prefix(1);
    k.normals = !prefix.empty() && prefix[0] == 'N';
    if (k.normals) prefix.remove_prefix(1);
    k.homogeneous = !prefix.empty() && prefix[0] == '4';
    if (k.homogeneous) prefix.remove_prefix(1);
    k.known = prefix.empty();
    return k;
}

void check_off_face_sizes(const std::string_view path, std::string_view bytes) {
    // CGAL's OFF scanner reads each line's numbers and then trusts them: a negative corner count
    // or index is cast to size_t, a colour beyond 255 to unsigned char, and a colour's entries are
    // read past the numbers the line has (ASan and UBSan found each). So every vertex and face
    // line is checked here the way the scanner will read it (File_scanner_OFF.h), and refused with
    // its line number unless each of those reads is in range.
    std::size_t pos = 0;
    int line_no = 0;
    std::string_view l;
    auto next_line = [&]() {
        while (pos < bytes.size()) {
            std::size_t eol = bytes.find('\n', pos);
            if (eol == std::string_view::npos) eol = bytes.size();
            l = bytes.substr(pos, eol - pos);
            pos = eol + 1;
            ++line_no;
            if (const std::size_t c = l.find('#'); c != std::string_view::npos) l = l.substr(0, c);
            TokenReader t{l};
            std::string_view first;
            if (t.next(first)) return true;
        }
        return false;
    };
    if (!next_line()) return;
    TokenReader head{l};
    std::string_view kw, a, b;
    if (!head.next(kw) || kw.find("OFF") == std::string_view::npos) return;  // not OFF: diagnose_mesh_file says so
    // "OFF#0 1 0": CGAL reads what follows a glued '#' as the counts, this check as a comment; the
    // two readings disagree (UBSan in CGAL on a fuzz input), so a glued comment is refused.
    if (const char* end = kw.data() + kw.size(); end < bytes.data() + bytes.size() && *end == '#')
        refuse(path, "not a valid off file: line " + std::to_string(line_no) +
                         ": a comment must be separated from the keyword '" + printable(kw) + "' by a space");
    if (kw.size() < 3 || kw.substr(kw.size() - 3) != "OFF")  // CGAL's scanner reads "COFF!4" as COFF
        refuse(path, "not a valid off file: the first word '" + printable(kw) +
                         "' is not an OFF keyword ([ST][C][N][4]OFF)");
    if (head.next(a) && a == "BINARY") return;  // check_off_counts bounds the binary form
    // The counts, on the keyword's line or the next: three integers and nothing else (CGAL reads
    // whatever follows them as the first vertex).
    auto check_counts_line = [&](TokenReader t, std::string_view first) {
        std::string_view tok = first;
        int n = 0;
        long long v = 0;
        do {
            if (!as_count(tok, v) || ++n > 3)
                refuse(path, "not a valid off file: line " + std::to_string(line_no) +
                                 ": the header's counts must be three non-negative integers, found '" +
                                 printable(tok) + "'");
            // CGAL doubles the edge count (ctmap ignores it) in an int: over 2^30 is signed overflow
            // (UBSan, a fuzz finding); no mesh a file can hold has that many edges.
            if (n == 3 && v > (1LL << 30))
                refuse(path, "not a valid off file: line " + std::to_string(line_no) + ": the header declares " +
                                 printable(tok) + " edges, more than any mesh ctmap reads (at most 2^30)");
        } while (t.next(tok));
        // Three: with two, CGAL takes the first number of the next line as the edge count.
        if (n < 3)
            refuse(path, "not a valid off file: line " + std::to_string(line_no) +
                             ": the header needs three counts (vertices, faces, edges)");
    };
    if (!a.empty()) check_counts_line(head, a);
    const auto [textures, colours, normals, homogeneous, known] = parse_off_keyword(kw);
    if (!known)
        refuse(path, "not a valid off file: the keyword '" + printable(kw) +
                         "' is not supported (ctmap reads [ST][C][N][4]OFF, text or BINARY)");
    const int H = homogeneous ? 1 : 0;
    long long nv = 0, nf = 0;
    if (a.empty()) {
        if (!next_line()) return;
        head = TokenReader{l};
        if (!head.next(a)) return;
        check_counts_line(head, a);
        head = TokenReader{l};
        head.next(a);
    } else {
        head = TokenReader{l};
        head.next(kw);
        head.next(a);
    }
    if (!as_count(a, nv) || !head.next(b) || !as_count(b, nf)) return;  // check_off_counts and the reader say so

    std::vector<double> entries;
    auto read_entries = [&](const std::string& who) {
        entries.clear();
        TokenReader t{l};
        std::string_view tok;
        while (t.next(tok)) {
            std::string_view num = tok;
            if (!num.empty() && num[0] == '+') num.remove_prefix(1);
            double v = 0;
            const auto [end, ec] = std::from_chars(num.data(), num.data() + num.size(), v);
            if (ec != std::errc() || end != num.data() + num.size() || !std::isfinite(v))
                refuse(path, "not a valid off file: line " + std::to_string(line_no) + ": " + who + ": '" +
                                 printable(tok) + "' is not a finite number");
            entries.push_back(v);
        }
    };
    auto at = [&](const std::string& who) { return "not a valid off file: line " + std::to_string(line_no) + ": " + who; };
    // A colour of `n` entries from entries[first]: 0, 1 (an index into CGAL's colour map), 3 or 4
    // (integers 0-255, or fractions 0-1).
    // Once a vertex (or face) line has a colour, CGAL's scanner reads one for every later line of
    // that kind, past the end of a line that has none (a heap overflow in scan_color).
    bool coloured[2] = {false, false};
    auto check_colour = [&](long long first, long long n, const std::string& who, int kind) {
        if (n == 0 && coloured[kind])
            refuse(path, at(who) + " has no colour, but an earlier " + (kind == 0 ? "vertex" : "face") +
                             " has one (give every one a colour, or none)");
        coloured[kind] |= n != 0;
        if (n != 0 && n != 1 && n != 3 && n != 4)
            refuse(path, at(who) + " has " + std::to_string(n) + " colour values (0, 1, 3 or 4 are allowed)");
        if (n == 1 && !(entries[first] >= 0 && entries[first] <= 255 && std::floor(entries[first]) == entries[first]))
            refuse(path, at(who) + ": a colour index must be an integer in [0, 255]");
        // CGAL reads three integers as 0-255, and otherwise multiplies all three by 255.
        bool fractions = false;
        for (long long k = first; k < first + 3 && n >= 3; ++k) fractions |= std::floor(entries[k]) != entries[k];
        for (long long k = first; k < first + 3 && n >= 3; ++k)
            if (!(entries[k] >= 0 && entries[k] <= (fractions ? 1 : 255)))
                refuse(path, at(who) + ": a colour is three integers in [0, 255] or three fractions in [0, 1]");
    };
    for (long long v = 0; v < nv; ++v) {
        if (!next_line())  // CGAL's scanner reads a colour from the missing line before it notices
            refuse(path, "not a valid off file: the file is truncated: the header declares " + std::to_string(nv) +
                             " vertices, but the file ends after " + std::to_string(v));
        const std::string who = "vertex " + std::to_string(v);
        read_entries(who);
        const long long coords = 3 + H, need = coords + (normals ? 3 + H : 0) + (textures ? 2 + H : 0);
        if ((long long)entries.size() < need)
            refuse(path, at(who) + " has " + std::to_string(entries.size()) + " numbers; the " + printable(kw) +
                             " header asks for at least " + std::to_string(need));
        if (colours) check_colour(coords + (normals ? 3 + H : 0), (long long)entries.size() - need, who, 0);
    }
    for (long long f = 0; f < nf; ++f) {
        if (!next_line())
            refuse(path, "not a valid off file: the file is truncated: the header declares " + std::to_string(nf) +
                             " faces, but the file ends after " + std::to_string(f));
        const std::string who = "face " + std::to_string(f);
        read_entries(who);
        const double n = entries[0];
        if (!(n >= 3 && std::floor(n) == n))
            refuse(path, at(who) + ": the corner count must be an integer of at least 3");
        if ((long double)n * 2 > (long double)(bytes.size() - std::min(pos, bytes.size())) + l.size())
            refuse(path, at(who) + " declares " + short_count(n) + " corners, more than the file holds");
        const long long corners = (long long)n;
        if ((long long)entries.size() < corners + 1)
            refuse(path, at(who) + " lists fewer than " + std::to_string(corners) + " vertex indices");
        for (long long k = 1; k <= corners; ++k)
            if (!(entries[k] >= 0 && entries[k] < double(nv) && std::floor(entries[k]) == entries[k]))
                refuse(path, at(who) + ": vertex index " + std::to_string(entries[k]) +
                                 " is not an integer in [0, " + std::to_string(nv) + ")");
        if (colours) check_colour(corners + 1, (long long)entries.size() - corners - 1, who, 1);
    }
}

}  // namespace ctmap
