// golden_set.hpp: the synthetic regression set (golden/regression-set.txt).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace hc::tools {

struct RegressionStream {
    std::string pattern;
    int width = 0;
    int height = 0;
    int frames = 0;
    int idle_every = 0;
};

std::vector<RegressionStream> read_regression_set(const std::filesystem::path& p);
/// "random_40x30": the stem of the stream's golden files.
std::string stream_stem(const RegressionStream& s);

}  // namespace hc::tools
