// standin_kitti.hpp: stand-in sequences in the KITTI odometry layout for the sharding
// tests (sequences/NN/image_0 and image_1, PNG frames 000000.png ...), generated from the
// moving synthetic patterns into a scratch directory.
#pragma once

#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <opencv2/imgcodecs.hpp>

#include "model/image/image.hpp"

namespace hc::test {

/// Writes `pairs` stereo pairs of `width` x `height` as KITTI sequence `seq` under
/// `root`/sequences; the right frame is the left one's pattern `seed + 1`.
inline void write_standin_sequence(const std::filesystem::path& root, const std::string& seq, int width, int height,
                                   int pairs, Pattern pattern = Pattern::blocks, std::uint32_t seed = 1) {
    for (int cam = 0; cam < 2; ++cam) {
        const std::filesystem::path d = root / "sequences" / seq / fmt::format("image_{}", cam);
        std::filesystem::create_directories(d);
        for (int k = 0; k < pairs; ++k) {
            const Image im = make_pattern(pattern, width, height, k, seed + static_cast<std::uint32_t>(cam));
            const cv::Mat m(im.height, im.width, CV_8UC1, const_cast<std::uint8_t*>(im.pixels.data()));
            cv::imwrite((d / fmt::format("{:06}.png", k)).string(), m);
        }
    }
}

}  // namespace hc::test
