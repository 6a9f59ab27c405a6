// types.hpp: the matrices that travel between stages (thesis D.b: matrix7u8, matrix5s11, ...).
#pragma once

#include <array>
#include <cstdint>

#include "model/fixed/word.hpp"

namespace hc {

using Pixel = std::uint8_t;
template <int N>
using PixelMatrix = std::array<std::array<Pixel, N>, N>;
using Window7 = PixelMatrix<7>;   ///< the 7x7 window entering the pipeline, [row][col] from 0
using Pixels3 = PixelMatrix<3>;   ///< a 3x3 neighbourhood of pixels

template <int N>
using WordMatrix = std::array<std::array<Word, N>, N>;
using Matrix5 = WordMatrix<5>;    ///< 5x5 gradients or M coefficients
using Matrix3 = WordMatrix<3>;    ///< 3x3 block sums or responses

/// The 3x3 sub-matrix of m whose top-left element is (i, j), counting from 0.
template <class M>
auto sub3(const M& m, int i, int j) {
    using E = std::remove_cvref_t<decltype(m[0][0])>;
    std::array<std::array<E, 3>, 3> s{};
    for (int di = 0; di < 3; ++di)
        for (int dj = 0; dj < 3; ++dj) s[di][dj] = m[i + di][j + dj];
    return s;
}

/// `c ? a : b` as a call: a stage function that chooses between two values this way also
/// runs on a symbolic word, whose comparisons give a symbolic condition (sweep/smt_word.hpp
/// has the overload on it).
template <class X>
constexpr X choose(bool c, const X& a, const X& b) {
    return c ? a : b;
}
/// The constant `v` in the number type of `x` (a plain integer here; sweep/smt_word.hpp has
/// the symbolic word's, at x's width and signedness).
constexpr long constant_like(long, long v) { return v; }

template <int N>
WordMatrix<N> filled(const Word& w) {
    WordMatrix<N> m;
    for (auto& row : m) row.fill(w);
    return m;
}

}  // namespace hc
