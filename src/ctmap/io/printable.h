#pragma once
/// \file printable.h
/// Text read from an input file, quoted in an error message: every byte outside printable ASCII
/// shown as '?' and the text cut after `max` bytes (with "..."), so that no terminal escape
/// sequence and no megabyte token of a corrupt file reaches the user's terminal.
#include <string>
#include <string_view>

namespace ctmap {

/// `s` as it may appear in a message (see above).
inline std::string printable(std::string_view s, std::size_t max = 64) {
    std::string out(s.substr(0, max));
    for (char& c : out)
        if (c < 0x20 || c > 0x7e) c = '?';
    if (s.size() > max) out += "...";
    return out;
}

/// `s` printable and in single quotes (a name in a message: a feature's, from JSON, may hold any
/// character).
inline std::string quoted_name(std::string_view s) { return "'" + printable(s) + "'"; }

}  // namespace ctmap
