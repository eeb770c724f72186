#pragma once
// The registration flags every tool shares (--k, --radius, --nu, --runs, ...), parsed in one
// place so pda_align, pda_benchmark and pda_bag_eval accept the same names and limits.

#include <set>
#include <string>

#include "pda_registration/tools/command_line.hpp"
#include "pda_registration/tools/method_runner.hpp"

namespace pda_registration {

/// Flag names (without "--") read by readSettingsFlags.
std::set<std::string> settingsFlagNames();

/// A parser for a tool: the shared registration flags, the tool's own value flags, and --help.
CommandLine commandLineWithSettings(const std::set<std::string>& tool_value_flags,
                                    const std::set<std::string>& tool_switches = {});

/// Help text for those flags, one per line, with defaults.
std::string settingsFlagsHelp();

/// Applies the flags present on the command line to *settings; false on a bad value
/// (command_line->error() says which). Flags in `skip` are left untouched.
bool readSettingsFlags(CommandLine* command_line, MethodSettings* settings,
                       const std::set<std::string>& skip = {});

/// How a registration tool starts: parses argv into *cl, prints `usage` and the shared flags'
/// help on --help, and reads the shared flags into *settings. Returns the exit code to leave with
/// (0 after --help; 2 on a bad flag, reported as "tool: error: ..."), or -1 to go on.
int startRegistrationTool(const std::string& tool, const char* usage, int argc, char** argv,
                          CommandLine* cl, MethodSettings* settings);

}  // namespace pda_registration
