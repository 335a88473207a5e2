#pragma once
/// \file atomic_file.h
/// Outputs are written to a temporary beside the target and renamed into place, so a failed run
/// never leaves a partial file (DESIGN §3).
#include <string>
#include <deque>

namespace ctmap {

/// One output file written through a temporary. Destroying it without `commit()` removes the
/// temporary; `commit()` renames it onto the target.
class AtomicFile {
public:
    /// Chooses the temporary `.<name>.tmp<pid>_<n>` beside `target` (nothing is created yet), and
    /// removes the temporaries of `target` left by runs that were killed (their process is gone).
    /// \throw BadInput if `target` names no file, is a folder, or its folder does not exist.
    explicit AtomicFile(std::string target);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    AtomicFile(AtomicFile&&) noexcept;

    const std::string& target() const { return target_; }
    const std::string& temp_path() const { return temp_; }
    /// Renames the temporary onto the target. \throw InternalError if the rename fails.
    void commit();

private:
    std::string target_;
    std::string temp_;
    bool committed_ = false;
};

/// Several outputs that appear together or not at all: each is written to its temporary, and
/// `commit_all()` renames them in order once every one is complete.
class OutputSet {
public:
    /// Registers an output and returns the temporary path to write it to.
    /// \throw BadInput as AtomicFile's constructor.
    std::string add(const std::string& target);
    /// Renames every temporary onto its target, in order. If one rename fails, the outputs
    /// already renamed are removed again, so the set appears whole or not at all.
    /// \throw InternalError if a rename fails.
    void commit_all();

private:
    std::deque<AtomicFile> files_;
};

/// Writes `content` to `path` atomically. \throw InternalError if it cannot be written.
void write_text_file(const std::string& path, const std::string& content);

}  // namespace ctmap
