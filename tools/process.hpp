// process.hpp: running a child program (the simulators, ghdl) and waiting for it.
#pragma once

#include <string>
#include <vector>

namespace hc::tools {

/// Runs argv[0] (a path) with the current environment plus `extra_env` ("NAME=value",
/// overriding); stdout/stderr are inherited, or sent to `log_file` when given. Returns the
/// exit status (128 + signal number if killed).
int run_process(const std::vector<std::string>& argv, const std::vector<std::string>& extra_env = {},
                const std::string& log_file = "");

}  // namespace hc::tools
