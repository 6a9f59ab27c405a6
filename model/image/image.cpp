#include "model/image/image.hpp"

#include <fstream>
#include <random>
#include <sstream>

#include "model/util/errors.hpp"

namespace hc {

namespace {
constexpr Pattern kPatterns[] = {Pattern::flat, Pattern::checkerboard, Pattern::random,
                                 Pattern::extremes, Pattern::blocks, Pattern::twins};
}  // namespace

Pattern parse_pattern(const std::string& name) {
    for (Pattern p : kPatterns)
        if (pattern_name(p) == name) return p;
    throw InputError("unknown pattern '" + name + "' (" + pattern_names() + ")");
}

std::string pattern_name(Pattern p) {
    switch (p) {
        case Pattern::flat: return "flat";
        case Pattern::checkerboard: return "checkerboard";
        case Pattern::random: return "random";
        case Pattern::extremes: return "extremes";
        case Pattern::blocks: return "blocks";
        case Pattern::twins: return "twins";
    }
    return "?";
}

std::string pattern_names() {
    std::string s;
    for (Pattern p : kPatterns) s += (s.empty() ? "" : ", ") + pattern_name(p);
    return s;
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
        case Pattern::twins: {   // half-turn symmetric blobs on grey, one every 10 pixels
            for (auto& px : img.pixels) px = 128;
            constexpr int kAxes[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
            std::uniform_int_distribution<int> off(-2, 2), dv(0, 255), dn(1, 4);
            int blob = index;
            for (int by = 5; by + 5 < height; by += 10)
                for (int bx = 5; bx + 5 < width; bx += 10, ++blob) {
                    // twins (bx, by) and (bx + dx, by + dy); (x, y) turns to (2bx + dx - x, 2by + dy - y)
                    const int dx = kAxes[blob % 4][0], dy = kAxes[blob % 4][1];
                    const auto twin = static_cast<std::uint8_t>(dv(rng) < 128 ? 0 : 255);
                    img.at(by, bx) = twin;   // the twins themselves black or white: the blob's peak
                    img.at(by + dy, bx + dx) = twin;
                    for (int k = dn(rng); k > 0; --k) {   // and a few more pixels, each with its image
                        const int x = bx + off(rng), y = by + off(rng);
                        const auto v = static_cast<std::uint8_t>(dv(rng));
                        img.at(y, x) = v;
                        img.at(2 * by + dy - y, 2 * bx + dx - x) = v;
                    }
                }
            break;
        }
    }
    return img;
}

std::string pgm_bytes(const Image& im) {
    std::string b = "P5\n" + std::to_string(im.width) + " " + std::to_string(im.height) + "\n255\n";
    b.append(reinterpret_cast<const char*>(im.pixels.data()), im.pixels.size());
    return b;
}

Image read_pgm(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError("PGM image '" + path + "' cannot be read");
    std::string magic;
    int w = 0, h = 0, maxval = 0;
    if (!(in >> magic >> w >> h >> maxval) || magic != "P5" || w <= 0 || h <= 0 || maxval != 255 || in.get() == EOF)
        throw InputError("'" + path + "' is not a binary 8-bit PGM (P5, maxval 255)");
    Image im(w, h);
    if (!in.read(reinterpret_cast<char*>(im.pixels.data()), static_cast<std::streamsize>(im.pixels.size())))
        throw InputError("PGM image '" + path + "' is shorter than " + std::to_string(w) + "x" + std::to_string(h) + " pixels");
    return im;
}

}  // namespace hc
