#include "model/image/image.hpp"

#include <random>

#include "util/errors.hpp"

namespace hc {

Pattern parse_pattern(const std::string& name) {
    if (name == "flat") return Pattern::flat;
    if (name == "checkerboard") return Pattern::checkerboard;
    if (name == "random") return Pattern::random;
    if (name == "extremes") return Pattern::extremes;
    if (name == "blocks") return Pattern::blocks;
    throw InputError("unknown pattern '" + name +
                                "' (flat, checkerboard, random, extremes, blocks)");
}

std::string pattern_name(Pattern p) {
    switch (p) {
        case Pattern::flat: return "flat";
        case Pattern::checkerboard: return "checkerboard";
        case Pattern::random: return "random";
        case Pattern::extremes: return "extremes";
        case Pattern::blocks: return "blocks";
    }
    return "?";
}

Image make_pattern(Pattern p, int width, int height, int index, std::uint32_t seed) {
    Image img(width, height);
    std::mt19937 rng(seed * 7919U + static_cast<std::uint32_t>(index));
    switch (p) {
        case Pattern::flat:   // one grey level per frame: no gradient at all
            for (auto& px : img.pixels) px = static_cast<std::uint8_t>(96 + 16 * index);
            break;
        case Pattern::checkerboard: {   // 8-pixel squares shifted by the frame index
            for (int r = 0; r < height; ++r)
                for (int c = 0; c < width; ++c)
                    img.at(r, c) = (((r + index) / 8 + (c + 2 * index) / 8) % 2) ? 230 : 25;
            break;
        }
        case Pattern::random: {
            std::uniform_int_distribution<int> d(0, 255);
            for (auto& px : img.pixels) px = static_cast<std::uint8_t>(d(rng));
            break;
        }
        case Pattern::extremes: {   // saturated 0/255 speckle: the widest gradients
            std::bernoulli_distribution d(0.5);
            for (auto& px : img.pixels) px = d(rng) ? 255 : 0;
            break;
        }
        case Pattern::blocks: {   // random rectangles on a gradient: isolated real corners
            for (int r = 0; r < height; ++r)
                for (int c = 0; c < width; ++c)
                    img.at(r, c) = static_cast<std::uint8_t>((r + c) * 60 / (width + height));
            std::uniform_int_distribution<int> dx(0, width - 1), dy(0, height - 1), dv(0, 255);
            const int n = 2 + width * height / 400;
            for (int k = 0; k < n; ++k) {
                const int x0 = dx(rng), y0 = dy(rng), v = dv(rng);
                const int x1 = std::min(width, x0 + 3 + dx(rng) % 12);
                const int y1 = std::min(height, y0 + 3 + dy(rng) % 12);
                for (int r = y0; r < y1; ++r)
                    for (int c = x0; c < x1; ++c) img.at(r, c) = static_cast<std::uint8_t>(v);
            }
            break;
        }
    }
    return img;
}

}  // namespace hc
