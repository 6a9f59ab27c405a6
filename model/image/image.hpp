// image.hpp: an 8-bit grayscale image, the only picture type the model and driver need.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace hc {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;   ///< row-major

    Image() = default;
    Image(int w, int h, std::uint8_t fill = 0)
        : width(w), height(h), pixels(static_cast<size_t>(w) * static_cast<size_t>(h), fill) {
        if (w <= 0 || h <= 0)
            throw std::invalid_argument("image size " + std::to_string(w) + "x" + std::to_string(h));
    }
    std::uint8_t at(int row, int col) const { return pixels[static_cast<size_t>(row) * width + col]; }
    std::uint8_t& at(int row, int col) { return pixels[static_cast<size_t>(row) * width + col]; }
    friend bool operator==(const Image&, const Image&) = default;
};

/// Synthetic test frames. `seed` makes random ones reproducible.
/// `twins`: blobs each symmetric under a half turn about the midpoint of two neighbouring
/// pixels (horizontal, vertical and both diagonal neighbours in turn), so that the two hold
/// exactly equal responses (the half turn negates both gradients, which leaves every
/// product, sum and truncation unchanged): ties at the local-maximum test.
enum class Pattern { flat, checkerboard, random, extremes, blocks, twins };
Pattern parse_pattern(const std::string& name);   ///< throws hc::InputError naming the pattern
std::string pattern_name(Pattern p);
/// Every pattern's name, comma-separated, in declaration order.
std::string pattern_names();
/// Frame `index` of a synthetic sequence: patterns move by a few pixels per frame so that
/// chained frames differ.
Image make_pattern(Pattern p, int width, int height, int index, std::uint32_t seed = 1);

/// Binary PGM (P5, maxval 255): the format of small committed stimuli (golden/witnesses/).
/// read_pgm throws hc::InputError naming the file when it is not such a PGM.
Image read_pgm(const std::string& path);
/// The PGM bytes of an image.
std::string pgm_bytes(const Image& im);

}  // namespace hc
