#pragma once
/// \file errors.h
/// The one small family of exceptions ctmap throws (DESIGN §3).
/// `BadInput` and its children mean the user's files are wrong (CLI exit 2);
/// `InternalError` and its children mean ctmap failed on valid input (CLI exit 3).
#include <stdexcept>
#include <string>

namespace ctmap {

/// Base of every ctmap exception.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The input is wrong: a file that cannot be read, a broken mesh, a bad features file.
/// The message names the file and the problem.
class BadInput : public Error {
public:
    BadInput(const std::string& file, const std::string& problem)
        : Error(file.empty() ? problem : file + ": " + problem), file_(file), problem_(problem) {}
    const std::string& file() const { return file_; }
    const std::string& problem() const { return problem_; }

private:
    std::string file_;
    std::string problem_;
};

/// The mesh has the wrong topology for the operation (not a disc, non-manifold, ...).
class TopologyError : public BadInput {
public:
    using BadInput::BadInput;
};

/// ctmap failed on input it accepted (a solver did not converge, an output could not be written).
class InternalError : public Error {
public:
    using Error::Error;
};

/// A linear solve failed.
class SolverError : public InternalError {
public:
    using InternalError::InternalError;
};

/// Runs `f()` and returns what it returns; a BadInput it throws that names no file is thrown again
/// naming `file`. The algorithms take no file names (issue 16): a caller that read the features
/// from a file (the CLI, the renderer) adds it to the message this way. A TopologyError is about
/// the mesh, not that file, and passes unchanged.
template <class F>
decltype(auto) naming_file(const std::string& file, F&& f) {
    try {
        return f();
    } catch (const TopologyError&) {
        throw;
    } catch (const BadInput& e) {
        if (!e.file().empty() || file.empty()) throw;
        throw BadInput(file, e.problem());
    }
}

/// Exit codes of the command-line program (DESIGN §3).
enum ExitCode : int { kExitOk = 0, kExitInvalid = 1, kExitBadInput = 2, kExitInternal = 3 };

}  // namespace ctmap
