// local_maximum.hpp: model of rtl/local_maximum.vhd.
//
// A corner when the centre is strictly greater than all 8 neighbours (ties suppress).
#pragma once

#include "harris/types.hpp"

namespace hc {

inline bool local_maximum(const Matrix3& r) {
    const Word& c = r[1][1];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if ((i != 1 || j != 1) && !(c > r[i][j])) return false;
    return true;
}

}  // namespace hc
