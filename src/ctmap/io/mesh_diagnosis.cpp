#include "ctmap/io/mesh_diagnosis.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include "ctmap/errors.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/mesh_precheck.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

using Tokens = std::vector<std::string_view>;

/// One non-empty line of a text mesh file, comments removed.
struct Line {
    int number = 0;  ///< 1-based line number in the file
    Tokens tokens;
};

std::string slurp(const std::string& path, std::size_t limit = std::size_t(1) << 30) {
    std::ifstream in(path, std::ios::binary);
    std::string s;
    char buf[1 << 16];
    while (s.size() < limit && in.read(buf, sizeof buf).gcount() > 0) s.append(buf, std::size_t(in.gcount()));
    return s;
}

Tokens split(std::string_view s) {
    Tokens out;
    std::size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && std::isspace((unsigned char)s[i])) ++i;
        const std::size_t start = i;
        while (i < s.size() && !std::isspace((unsigned char)s[i])) ++i;
        if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
}

/// The file's non-empty lines, with everything after `comment` removed (no comment when 0).
std::vector<Line> text_lines(std::string_view text, char comment) {
    std::vector<Line> out;
    int number = 0;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        std::string_view line = text.substr(pos, end - pos);
        ++number;
        if (comment)
            if (const std::size_t c = line.find(comment); c != std::string_view::npos) line = line.substr(0, c);
        Line l{number, split(line)};
        if (!l.tokens.empty()) out.push_back(std::move(l));
        pos = end + 1;
    }
    return out;
}

/// Binary bytes where text is expected: a NUL, or many control characters in the first 4 KiB.
bool looks_binary(std::string_view text) {
    const std::string_view head = text.substr(0, 4096);
    std::size_t control = 0;
    for (unsigned char c : head) {
        if (c == 0) return true;
        if (c < 32 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v') ++control;
    }
    return control * 20 > head.size();
}

std::string binary_message(const std::string& format) {
    const std::string article = format == "PLY" ? "a " : "an ";
    return "binary data where " + format + " text was expected (not " + article + format +
           " file, or a corrupted one)";
}

std::string at_line(int line) { return "line " + std::to_string(line) + ": "; }

/// Empty if `tok` is a finite number, else what is wrong with it.
std::string number_problem(std::string_view tok) {
    if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
    double v = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), v);
    const std::string quoted = "'" + printable(tok) + "'";
    if (ec == std::errc::result_out_of_range) return "the number " + quoted + " is out of the range of a double";
    if (ec != std::errc() || end != tok.data() + tok.size()) return quoted + " is not a number";
    if (!std::isfinite(v)) return "the coordinate " + quoted + " is not finite (NaN or infinity)";
    return {};
}

/// Empty if `tok` is a non-negative integer below `count`, else what is wrong with it.
std::string index_problem(std::string_view tok, long long count, const std::string& who) {
    long long i = 0;
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), i);
    if (ec != std::errc() || end != tok.data() + tok.size() || i < 0)
        return who + ": '" + printable(tok) + "' is not a vertex index";
    if (i >= count)
        return who + " uses vertex " + std::to_string(i) + ", which is out of range (the file has " +
               std::to_string(count) + " vertices)";
    return {};
}

/// The first problem among the first `n` coordinates of a vertex line.
std::string vertex_problem(const Line& l, std::size_t first, std::size_t n, long long index) {
    const std::string who = at_line(l.number) + "vertex " + std::to_string(index);
    if (l.tokens.size() < first + n) return who + " has fewer than " + std::to_string(n) + " coordinates";
    for (std::size_t k = first; k < first + n; ++k)
        if (std::string p = number_problem(l.tokens[k]); !p.empty()) return who + ": " + p;
    return {};
}

/// The first problem in a face line "n i1 ... in" (OFF and ASCII PLY).
std::string counted_face_problem(const Line& l, long long index, long long num_vertices) {
    const std::string who = at_line(l.number) + "face " + std::to_string(index);
    long long n = 0;
    const std::string_view t = l.tokens[0];
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), n);
    if (ec != std::errc() || end != t.data() + t.size() || n < 0)
        return who + ": '" + printable(t) + "' is not a corner count";
    if (n < 3) return who + " has " + std::to_string(n) + " corners; a face needs at least 3";
    if ((long long)l.tokens.size() < n + 1) return who + " lists fewer than " + std::to_string(n) + " vertex indices";
    for (long long k = 1; k <= n; ++k)
        if (std::string p = index_problem(l.tokens[k], num_vertices, who); !p.empty()) return p;
    return {};
}

std::string truncated(long long declared, const char* what, long long found) {
    return "the file is truncated: the header declares " + std::to_string(declared) + " " + what +
           ", but the file ends after " + std::to_string(found);
}

bool ends_with(std::string_view s, std::string_view suffix) {
    return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

/// The counts of an OFF header: vertices, faces (text form). False if the header is unreadable.
bool off_counts(const std::vector<Line>& lines, std::size_t& body, long long& nv, long long& nf) {
    if (lines.empty() || !ends_with(lines[0].tokens[0], "OFF")) return false;
    Tokens counts(lines[0].tokens.begin() + 1, lines[0].tokens.end());
    body = 1;
    if (counts.empty() && lines.size() > 1) counts = lines[body++].tokens;
    if (counts.size() < 2) return false;
    auto as_int = [](std::string_view t, long long& v) {
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        return ec == std::errc() && end == t.data() + t.size() && v >= 0;
    };
    return as_int(counts[0], nv) && as_int(counts[1], nf);
}

std::string diagnose_off(std::string_view text) {
    if (looks_binary(text) && text.find("BINARY") == std::string_view::npos) return binary_message("OFF");
    const std::vector<Line> lines = text_lines(text, '#');
    if (lines.empty() || !ends_with(lines[0].tokens[0], "OFF"))
        return "the file does not start with an OFF header (found '" +
               (lines.empty() ? std::string() : printable(lines[0].tokens[0])) + "')";
    if (lines[0].tokens.size() > 1 && lines[0].tokens[1] == "BINARY") return {};
    std::size_t body = 0;
    long long nv = 0, nf = 0;
    if (!off_counts(lines, body, nv, nf))
        return "the OFF header must give the vertex, face and edge counts as non-negative integers";
    const std::size_t first = lines[0].tokens[0].find('4') != std::string_view::npos ? 4 : 3;
    for (long long v = 0; v < nv; ++v) {
        if (body >= lines.size()) return truncated(nv, "vertices", v);
        if (std::string p = vertex_problem(lines[body++], 0, first, v); !p.empty()) return p;
    }
    for (long long f = 0; f < nf; ++f) {
        if (body >= lines.size()) return truncated(nf, "faces", f);
        if (std::string p = counted_face_problem(lines[body++], f, nv); !p.empty()) return p;
    }
    return {};
}

/// The first problem in an OBJ face line: corners "v", "v/vt", "v/vt/vn", "v//vn".
std::string obj_face_problem(const Line& l, long long face, long long vertices_so_far, long long num_vertices) {
    const std::string who = at_line(l.number) + "face " + std::to_string(face);
    if (l.tokens.size() < 4)
        return who + " has " + std::to_string(l.tokens.size() - 1) + " corners; a face needs at least 3";
    for (std::size_t k = 1; k < l.tokens.size(); ++k) {
        std::string_view t = l.tokens[k].substr(0, l.tokens[k].find('/'));
        long long i = 0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), i);
        if (ec != std::errc() || end != t.data() + t.size() || i == 0)
            return who + ": '" + printable(l.tokens[k]) + "' is not a vertex index";
        const long long resolved = i > 0 ? i : vertices_so_far + i + 1;  // negative: relative
        if (resolved < 1 || resolved > num_vertices)
            return who + " uses vertex " + std::to_string(i) + ", which is out of range (the file has " +
                   std::to_string(num_vertices) + " vertices; OBJ counts from 1)";
    }
    return {};
}

std::string diagnose_obj(std::string_view text) {
    if (looks_binary(text)) return binary_message("OBJ");
    const std::vector<Line> lines = text_lines(text, '#');
    const long long nv = std::count_if(lines.begin(), lines.end(), [](const Line& l) { return l.tokens[0] == "v"; });
    if (nv == 0) return "no vertices ('v' lines): not an OBJ mesh";
    long long v = 0, f = 0;
    for (const Line& l : lines) {
        if (l.tokens[0] == "v") {
            if (std::string p = vertex_problem(l, 1, 3, v++); !p.empty()) return p;
        } else if (l.tokens[0] == "f") {
            if (std::string p = obj_face_problem(l, f++, v, nv); !p.empty()) return p;
        }
    }
    return {};
}

/// One element of a PLY header.
struct PlyElement {
    std::string name;
    long long count = 0;
    long long min_bytes = 0;  ///< the least bytes one element takes in a binary file
};

long long ply_type_size(std::string_view t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "double" || t == "float64") return 8;
    return 4;
}

/// The header's elements, the format, and the byte offset where the data starts.
bool ply_header(std::string_view text, std::vector<PlyElement>& elements, std::string& format, std::size_t& data) {
    const std::size_t end = text.find("end_header");
    if (end == std::string_view::npos) return false;
    data = text.find('\n', end);
    data = data == std::string_view::npos ? text.size() : data + 1;
    for (const Line& l : text_lines(text.substr(0, end), 0)) {
        const Tokens& t = l.tokens;
        if (t[0] == "format" && t.size() > 1) format = std::string(t[1]);
        if (t[0] == "element" && t.size() > 2) {
            PlyElement e{std::string(t[1]), 0, 0};
            std::from_chars(t[2].data(), t[2].data() + t[2].size(), e.count);
            elements.push_back(e);
        }
        if (t[0] == "property" && t.size() > 2 && !elements.empty())
            elements.back().min_bytes += ply_type_size(t[1] == "list" ? t[2] : t[1]);
    }
    return true;
}

std::string diagnose_ply_binary(const std::vector<PlyElement>& elements, std::size_t data, std::size_t size) {
    long double need = 0;
    for (const PlyElement& e : elements) need += (long double)e.count * e.min_bytes;
    if (need > (long double)(size - data))
        return "the file is truncated: its header declares data of at least " + std::to_string((long long)need) +
               " bytes, but only " + std::to_string(size - data) + " follow the header";
    return {};
}

std::string diagnose_ply_ascii(const std::vector<PlyElement>& elements, std::string_view body, int line_offset) {
    std::vector<Line> lines = text_lines(body, 0);
    for (Line& l : lines) l.number += line_offset;
    long long nv = 0;
    std::size_t at = 0;
    for (const PlyElement& e : elements) {
        if (e.name == "vertex") nv = e.count;
        for (long long i = 0; i < e.count; ++i) {
            if (at >= lines.size()) return truncated(e.count, (printable(e.name) + " elements").c_str(), i);
            const Line& l = lines[at++];
            std::string p = e.name == "vertex" ? vertex_problem(l, 0, 3, i)
                            : e.name == "face" ? counted_face_problem(l, i, nv)
                                               : std::string();
            if (!p.empty()) return p;
        }
    }
    return {};
}

std::string diagnose_ply(std::string_view text) {
    if (text.substr(0, 3) != "ply")
        return looks_binary(text) ? binary_message("PLY") : "not a PLY file: it does not start with 'ply'";
    std::vector<PlyElement> elements;
    std::string format;
    std::size_t data = 0;
    if (!ply_header(text, elements, format, data)) return "the PLY header has no 'end_header' line";
    if (format != "ascii") return diagnose_ply_binary(elements, data, text.size());
    const int header_lines = int(std::count(text.begin(), text.begin() + data, '\n'));
    return diagnose_ply_ascii(elements, text.substr(data), header_lines);
}

std::string diagnose_stl_binary(std::string_view text) {
    if (text.size() < 84)
        return "not an STL file: it does not start with 'solid' (ASCII STL) and is shorter than the 84-byte "
               "header of a binary STL";
    std::uint32_t n = 0;
    std::memcpy(&n, text.data() + 80, 4);  // little-endian on every platform ctmap builds on
    const long long need = 84 + 50LL * n;
    if (need != (long long)text.size())
        return "read as a binary STL, its header declares " + std::to_string(n) + " triangles (" +
               std::to_string(need) + " bytes), but the file has " + std::to_string(text.size()) +
               " bytes (truncated, or binary garbage)";
    return {};
}

std::string diagnose_stl(std::string_view text) {
    const std::size_t start = text.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos || text.substr(start, 5) != "solid") return diagnose_stl_binary(text);
    long long v = 0;
    bool closed = false;
    for (const Line& l : text_lines(text, 0)) {
        if (l.tokens[0] == "vertex")
            if (std::string p = vertex_problem(l, 1, 3, v++); !p.empty()) return p;
        if (l.tokens[0] == "endsolid") closed = true;
    }
    if (!closed) return "the file is truncated: the ASCII STL has no 'endsolid' line";
    return {};
}

/// A big-endian 32-bit integer at byte `at` of `bytes` (the caller checks that it is there).
std::int32_t be32(std::string_view bytes, std::size_t at) {
    const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + at);
    return std::int32_t((std::uint32_t(b[0]) << 24) | (std::uint32_t(b[1]) << 16) | (std::uint32_t(b[2]) << 8) | b[3]);
}

/// BINARY OFF, walked as CGAL's scanner reads it: three big-endian counts after the keyword line,
/// then per vertex its floats, per face a corner count and that many indices. CGAL allocates the
/// counts before reading, so each is checked against the bytes that are left (a 27-byte fuzz
/// input declared a face of 233 million corners: a 1.8 GB allocation).
void check_binary_off(const std::string& path, std::string_view bytes, std::string_view keyword) {
    const std::size_t eol = bytes.find('\n');
    if (eol == std::string_view::npos || bytes.size() < eol + 1 + 12)
        throw BadInput(path, "not a valid off file: the BINARY header's three counts are missing");
    const long long nv = be32(bytes, eol + 1), nf = be32(bytes, eol + 5), ne = be32(bytes, eol + 9);
    if (nv < 0 || nf < 0) throw BadInput(path, "the OFF header declares a negative number of vertices or faces");
    // The edge count, which CGAL doubles in an int (signed overflow past 2^30; ctmap ignores it).
    if (ne < 0 || ne > (1 << 30))
        throw BadInput(path, "the OFF header declares " + std::to_string(ne) +
                                 " edges (negative or over 2^30: a corrupt header)");
    const OffKeyword kw = parse_off_keyword(keyword);
    const long long h = kw.homogeneous ? 1 : 0;
    const long long vertex_bytes = 4 * ((3 + h) + (kw.normals ? 3 + h : 0) + (kw.colours ? 3 : 0) + (kw.textures ? 2 + h : 0));
    const long long size = (long long)bytes.size();
    long long at = (long long)eol + 13;
    if ((long double)nv * vertex_bytes + (long double)nf * 16 > (long double)(size - at))
        throw BadInput(path, "the file is truncated: the header declares " + std::to_string(nv) + " vertices and " +
                                 std::to_string(nf) + " faces, which cannot fit in its " + std::to_string(size) +
                                 " bytes");
    at += nv * vertex_bytes;
    for (long long f = 0; f < nf; ++f) {
        if (at + 4 > size) throw BadInput(path, "the file is truncated: it ends at face " + std::to_string(f));
        const long long n = be32(bytes, (std::size_t)at);
        if (n < 3 || n > (size - at - 4) / 4)
            throw BadInput(path, "not a valid off file: face " + std::to_string(f) + " declares " + std::to_string(n) +
                                     " corners (" + (n < 3 ? "a face needs at least 3" : "more than the file holds") +
                                     ")");
        at += 4 + 4 * n;
    }
}

/// OFF: the declared counts must fit in the file (CGAL's reader allocates them first).
void check_off_counts(const std::string& path, std::string_view file_bytes) {
    const std::string_view text = file_bytes.substr(0, std::min(file_bytes.find('\0'), std::size_t(1) << 16));
    const std::vector<Line> lines = text_lines(text, '#');  // a binary header's text
    if (!lines.empty() && lines[0].tokens.size() > 1 && lines[0].tokens[1] == "BINARY" &&
        ends_with(lines[0].tokens[0], "OFF"))
        return check_binary_off(path, file_bytes, lines[0].tokens[0]);
    std::size_t body = 0;
    long long nv = 0, nf = 0;
    if (!off_counts(lines, body, nv, nf)) return;
    const long long size = (long long)file_bytes.size();
    if ((long double)nv * 6 + (long double)nf * 8 > (long double)size)  // "0 0 0\n", "3 0 1 2\n"
        throw BadInput(path, "the file is truncated: the header declares " + std::to_string(nv) + " vertices and " +
                                 std::to_string(nf) + " faces, which cannot fit in its " + std::to_string(size) +
                                 " bytes");
}

/// Binary STL: CGAL merges equal corners through an ordered map, where a NaN corner silently
/// becomes some other vertex; so every coordinate is checked here, before CGAL sees it.
void check_binary_stl(const std::string& path, const std::string& text) {
    const std::size_t start = text.find_first_not_of(" \t\r\n");
    if (start != std::string::npos && text.compare(start, 5, "solid") == 0) return;  // ASCII STL
    if (std::string p = diagnose_stl_binary(text); !p.empty()) throw BadInput(path, "not a valid stl file: " + p);
    const std::uint32_t n = std::uint32_t((text.size() - 84) / 50);
    for (std::uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 9; ++k) {
            float x = 0;
            std::memcpy(&x, text.data() + 84 + 50 * std::size_t(t) + 12 + 4 * k, 4);
            if (!std::isfinite(x))
                throw BadInput(path, "triangle " + std::to_string(t) + " has a non-finite coordinate (NaN or infinity)");
        }
}

}  // namespace

void check_before_reading(const std::string& path, const std::string& ext, const std::string& file_bytes) {
    if (ext == ".off" || ext == ".ply") {
        const std::string_view bytes = std::string_view(file_bytes).substr(utf8_bom_length(file_bytes));
        try {
            if (ext == ".ply") check_ply_declarations(path, bytes);
            else check_off_face_sizes(path, bytes);
        } catch (const BadInput&) {  // OFF: the diagnosis names the problem in the readers' own words, if it can
            const std::string why = ext == ".ply" ? std::string() : diagnose_off(bytes);
            if (!why.empty()) throw BadInput(path, "not a valid " + ext.substr(1) + " file: " + why);
            throw;
        }
    }
    if (ext == ".off") check_off_counts(path, std::string_view(file_bytes).substr(utf8_bom_length(file_bytes)));
    if (ext == ".stl") check_binary_stl(path, file_bytes);
}

std::string diagnose_mesh_file(const std::string& path, const std::string& ext) {
    std::string text = slurp(path);
    text.erase(0, utf8_bom_length(text));  // the readers skip it too (read_mesh.cpp)
    if (ext == ".off") return diagnose_off(text);
    if (ext == ".obj") return diagnose_obj(text);
    if (ext == ".ply") return diagnose_ply(text);
    if (ext == ".stl") return diagnose_stl(text);
    return {};
}

}  // namespace ctmap
