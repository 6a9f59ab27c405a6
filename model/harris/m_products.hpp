// m_products.hpp: model of rtl/m_products.vhd (combinational part).
//
// a = ix*ix, b = ix*iy, c = iy*iy: each full product resized to m_prod_w with numeric_std
// semantics, then bits m_prod_w-1 .. m_drop kept (drop m_drop LSBs: floor(x / 2^m_drop)).
#pragma once

#include "harris/harris_pkg.hpp"
#include "harris/types.hpp"

namespace hc {

struct MProducts {
    Word a, b, c;
};

inline Word m_product(const Word& x, const Word& y, const Formats& f) {
    const Word full = resize(x * y, f.m_prod_w);
    return slice(full, f.m_prod_w - 1, f.m_drop);   // 21 -> 16 bits: drop 5 LSBs
}

inline MProducts m_products(const Word& ix, const Word& iy, const Formats& f) {
    return {m_product(ix, ix, f), m_product(ix, iy, f), m_product(iy, iy, f)};
}

}  // namespace hc
