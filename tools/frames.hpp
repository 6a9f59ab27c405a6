// frames.hpp: loading the frames a run streams through the design, from image files, a
// KITTI-layout sequence or a synthetic pattern, with errors that name the input.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "image/image.hpp"

namespace hc::tools {

/// Thrown for bad user input; the CLI prints what() and exits with status 2.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Reads an 8-bit image (grey, or colour converted to grey). Throws InputError naming the
/// file when it is missing, unreadable or not 8-bit.
Image load_image(const std::filesystem::path& p);

/// A centred crop of `width` x `height` (0 = keep). Throws InputError if larger than img.
Image crop(const Image& img, int width, int height, const std::string& what);

/// The data directory: --data, else $HARRIS_COSIM_DATA, else ../shared/data next to the
/// source tree (HC_DEFAULT_DATA_DIR at build time). Empty if none exists.
std::optional<std::filesystem::path> data_dir(const std::string& flag_value);

/// A KITTI odometry sequence: sequences/NN/image_0 (left) and image_1 (right).
struct KittiSequence {
    std::filesystem::path root;   ///< .../sequences/NN
    std::vector<std::filesystem::path> left, right;   ///< sorted; right may be shorter
};
/// Throws InputError when the directory is not a KITTI sequence.
KittiSequence open_kitti(const std::filesystem::path& kitti_dir, const std::string& sequence);

/// The thesis's evaluation stream L0 R0 L1 R1 ... for stereo frames [first, last).
/// Stereo pairs only; a pair whose right image is missing ends the stream.
std::vector<std::filesystem::path> stereo_stream(const KittiSequence& s, int first, int last);

/// Writes `bytes` to `target` atomically: a temporary beside it, then a rename, so that an
/// interrupted run never leaves half a file and never destroys an existing one early.
void write_file_atomic(const std::filesystem::path& target, const std::string& bytes);

}  // namespace hc::tools
