#pragma once
/// \file printable.h
/// Text read from an input file, put in a message: no control character, no invalid UTF-8 and no
/// megabyte token of a corrupt file reaches the user's terminal. Valid UTF-8 is kept ("œil" stays
/// readable); control characters (C0, DEL, C1) and bytes that are not valid UTF-8 are shown as '?'.
#include <string>
#include <string_view>

namespace ctmap {

namespace detail {
/// The length of the valid UTF-8 character at s[i] that is not a control character, or 0.
inline std::size_t printable_char(std::string_view s, std::size_t i) {
    const auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = b(i);
    if (c >= 0x20 && c < 0x7f) return 1;
    std::size_t n = c >= 0xc2 && c <= 0xdf ? 2 : c >= 0xe0 && c <= 0xef ? 3 : c >= 0xf0 && c <= 0xf4 ? 4 : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (std::size_t k = 1; k < n; ++k)
        if ((b(i + k) & 0xc0) != 0x80) return 0;
    if (c == 0xc2 && b(i + 1) < 0xa0) return 0;                          // C1 controls U+0080..U+009F
    if (c == 0xe0 && b(i + 1) < 0xa0) return 0;                          // overlong
    if (c == 0xed && b(i + 1) >= 0xa0) return 0;                         // surrogates
    if (c == 0xf0 && b(i + 1) < 0x90) return 0;                          // overlong
    if (c == 0xf4 && b(i + 1) >= 0x90) return 0;                         // above U+10FFFF
    return n;
}

inline std::string sanitised(std::string_view s, std::size_t max, bool keep_lines) {
    std::string out;
    std::size_t i = 0;
    while (i < s.size() && i < max) {
        const char c = s[i];
        if (keep_lines && (c == '\n' || c == '\t')) {
            out += c, ++i;
            continue;
        }
        const std::size_t n = printable_char(s, i);
        if (n == 0) out += '?', ++i;
        else out.append(s.substr(i, n)), i += n;
    }
    if (i < s.size()) out += "...";
    return out;
}
}  // namespace detail

/// `s` on one line as it may appear in a message (see above), cut after about `max` bytes with
/// "...": a name or token of an input file.
inline std::string printable(std::string_view s, std::size_t max = 64) { return detail::sanitised(s, max, false); }

/// `s` printable and in single quotes (a name in a message: a feature's, from JSON, may hold any
/// character).
inline std::string quoted_name(std::string_view s) { return "'" + printable(s) + "'"; }

/// A whole message for the terminal: as `printable`, but keeping its line breaks and tabs and its
/// length (the command line's last word on every message it prints, whatever put text in it).
inline std::string terminal_text(std::string_view s) { return detail::sanitised(s, std::string_view::npos, true); }

}  // namespace ctmap
