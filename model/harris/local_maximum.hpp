// local_maximum.hpp: model of rtl/local_maximum.vhd.
//
// A corner when the centre is strictly greater than all 8 neighbours (ties suppress).
// Template over the 3x3 matrix type (Matrix3 of Word, or of LeanWord, or of the stage
// proofs' symbolic word, sweep/smt_word.hpp, on which it gives a symbolic condition).
#pragma once

#include "model/harris/types.hpp"

namespace hc {

template <class M>
inline auto local_maximum(const M& r) {
    const auto& c = r[1][1];
    auto all = c > r[0][0];   // bool, or the symbolic word's condition
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if ((i != 1 || j != 1) && (i != 0 || j != 0)) all = all && (c > r[i][j]);
    return all;
}

}  // namespace hc
