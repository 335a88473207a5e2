// ctmap's subcommands that live in their own files (apps/ctmap/cmd_<name>.cpp). Each file adds
// its subcommand to the app and returns what to run when it was chosen, so main.cpp stays a list.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>

namespace ctmap::cli {

struct Command {
    CLI::App* sub = nullptr;       ///< the subcommand, as added to the app
    std::function<int()> run;      ///< runs it after parsing; returns the exit code (DESIGN §3)
};

Command add_render_command(CLI::App& app);  // cmd_render.cpp

}  // namespace ctmap::cli
