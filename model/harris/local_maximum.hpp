// local_maximum.hpp: model of rtl/local_maximum.vhd.
//
// A corner when the centre is strictly greater than all 8 neighbours (ties suppress).
// Template over the 3x3 matrix type (Matrix3 of Word, or of LeanWord).
#pragma once

#include "model/harris/types.hpp"

namespace hc {

template <class M>
inline bool local_maximum(const M& r) {
    const auto& c = r[1][1];
    bool all = true;   // no early exit: the 8 comparisons stay branch-free
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (i != 1 || j != 1) all = all && (c > r[i][j]);
    return all;
}

}  // namespace hc
