// The bad-input suites' contract (test_bad_input*.cpp): a case runs the real `ctmap` program on
// broken files and must get exit code 2, a message naming the file and the problem, no crash,
// and nothing left behind.
#pragma once
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ctmap/errors.h"
#include "test_support.h"

namespace ctmap::test {

// ---------------------------------------------------------------------------------------------
// The contract every case checks.

/// What a case runs: the ctmap arguments, the file the message must name, and the words that
/// must appear in the message (the problem).
struct CliRun {
    std::string args;
    std::string names_file;
    std::vector<std::string> keywords;
};

struct Case {
    const char* name;
    std::function<CliRun(const TempDir&)> make;  ///< writes the broken file(s) into the folder
};

inline void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

/// Exit code 2, no crash and no sanitizer report, the file and the problem named, and no output
/// or temporary left in the folder.
inline void expect_rejected(const TempDir& dir, const CliRun& run) {
    const int entries_before = dir.count();
    const RunResult r = run_ctmap(run.args);
    SCOPED_TRACE("ctmap " + run.args + "\n" + r.out);
    EXPECT_LT(r.code, 128) << "ctmap crashed (killed by a signal)";
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_EQ(r.out.find("Sanitizer"), std::string::npos);
    EXPECT_EQ(r.out.find("runtime error"), std::string::npos);
    EXPECT_NE(r.out.find("ctmap: error: "), std::string::npos) << "the message is not ctmap's error line";
    EXPECT_NE(r.out.find(run.names_file), std::string::npos) << "the message does not name " << run.names_file;
    for (const std::string& k : run.keywords)
        EXPECT_NE(r.out.find(k), std::string::npos) << "the message does not say '" << k << "'";
    for (const char* out : {"out.obj", "out.mtl", "out.glb"})  // (a case may put a folder there)
        EXPECT_FALSE(std::filesystem::is_regular_file(dir / out)) << out << " was left behind";
    EXPECT_EQ(dir.count(), entries_before) << "a file (a temporary?) was left in the output folder";
}

}  // namespace ctmap::test
