// Each run flag (rigs/run/run_flags.hpp) as a CLI11 option: its help text, its check, and the
// typed RunOptions field it parses into, written once for every command that takes it.
#pragma once

#include <CLI/CLI.hpp>

#include <initializer_list>

#include "rigs/run/run_flags.hpp"
#include "rigs/run/run_options.hpp"

namespace a3::rigs {

CLI::Option* add_run_flag(CLI::App& cmd, RunOptions& options, RunFlag flag);
void add_run_flags(CLI::App& cmd, RunOptions& options, std::initializer_list<RunFlag> flags);

}  // namespace a3::rigs
