// data_dir_holding.hpp: the data directory of a data test (io/frames/frames.hpp data_dir),
// when it holds what the test reads; otherwise the test's main prints why and exits 77,
// which CTest counts as skipped.
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "io/frames/frames.hpp"

namespace hc::frames::test {

/// The data directory when `relative` exists in it; else nullopt after printing "SKIPPED: "
/// and the reason (no data directory, an unusable one, or no `relative` in it).
inline std::optional<std::filesystem::path> data_dir_holding(const std::string& relative) {
    std::optional<std::filesystem::path> d;
    try {
        d = data_dir("");
    } catch (const InputError& e) {
        std::printf("SKIPPED: %s\n", e.what());
        return std::nullopt;
    }
    if (!d || !std::filesystem::exists(*d / relative)) {
        std::printf("SKIPPED: no %s in the data directory (set HARRIS_COSIM_DATA to a directory holding it; "
                    "see the data README.md (../shared/data beside the repository))\n",
                    relative.c_str());
        return std::nullopt;
    }
    return d;
}

}  // namespace hc::frames::test
