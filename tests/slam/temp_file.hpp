// temp_file.hpp: a text file in the temporary directory, for the tests of the readers of
// mapping/slam (pose, trajectory and timestamp files).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace hc::slam::test {

/// Writes `text` to `slam_test_<pid>_<name>` in the temporary directory; returns its path.
inline std::filesystem::path temp_file(const std::string& name, const std::string& text) {
    const std::filesystem::path p =
        std::filesystem::temp_directory_path() / ("slam_test_" + std::to_string(::getpid()) + "_" + name);
    std::ofstream(p) << text;
    return p;
}

}  // namespace hc::slam::test
