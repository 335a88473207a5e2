// Progress lines of long commands on stderr (`ctmap map`), shared by the one-chart and the
// charts path.
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace ctmap::cli {

/// Progress on stderr. On a terminal: one line rewritten in place, cleared at the end. Elsewhere
/// (a log of a long job): a line when a stage that ran longer than a second ends, and a line
/// every 5 seconds within a long stage.
class Progress {
public:
    using Clock = std::chrono::steady_clock;
    Progress(bool enabled, bool terminal, std::string prefix = "ctmap map: ")
        : on_(enabled), terminal_(terminal), prefix_(std::move(prefix)) {}
    ~Progress() { clear(); }
    void operator()(const std::string& stage, int done, int total) {
        if (!on_) return;
        const auto now = Clock::now();
        if (stage != stage_) {
            finish(now);
            stage_ = stage;
            stage_start_ = last_line_ = now;
        }
        std::string line = prefix_ + stage;
        if (total > 0) line += " " + std::to_string(done) + "/" + std::to_string(total);
        if (terminal_) {
            std::fprintf(stderr, "\r%-60s", line.c_str());
            shown_ = true;
        } else if (seconds(last_line_, now) >= 5) {
            std::fprintf(stderr, "%s (%.0f s)\n", line.c_str(), seconds(stage_start_, now));
            last_line_ = now;
        }
        std::fflush(stderr);
    }
    /// Ends the last stage (its line, off a terminal) and clears the terminal's line.
    void clear() {
        finish(Clock::now());
        stage_.clear();
        if (!shown_) return;
        std::fprintf(stderr, "\r%-60s\r", "");
        std::fflush(stderr);
        shown_ = false;
    }

private:
    static double seconds(Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double>(b - a).count();
    }
    void finish(Clock::time_point now) {
        if (!on_ || terminal_ || stage_.empty() || seconds(stage_start_, now) < 1) return;
        std::fprintf(stderr, "%s%s done in %.1f s\n", prefix_.c_str(), stage_.c_str(), seconds(stage_start_, now));
        std::fflush(stderr);
    }
    bool on_, terminal_;
    std::string prefix_;
    bool shown_ = false;
    std::string stage_;
    Clock::time_point stage_start_, last_line_;
};

}  // namespace ctmap::cli
