#pragma once
/// \file subcommands.hpp
/// The function of each row of the command table (commands.cpp): each takes the parsed
/// arguments (cli/command.hpp) and returns the exit status; errors are thrown, and the
/// dispatcher turns them into one line.
#include "hexdyn/cli/command.hpp"

namespace hexdyn::cli {

int run_command(const Args& args);         ///< scene_commands.cpp
int validate_command(const Args& args);    ///< scene_commands.cpp
int sweep_command(const Args& args);       ///< the program's (Program::sweep)
int envelope_command(const Args& args);    ///< envelope_command.cpp
int replay_command(const Args& args);      ///< replay_command.cpp
int robustness_command(const Args& args);  ///< robustness_command.cpp

}  // namespace hexdyn::cli
