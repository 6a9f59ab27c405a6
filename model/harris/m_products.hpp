// m_products.hpp: model of rtl/m_products.vhd (combinational part).
//
// a = ix*ix, b = ix*iy, c = iy*iy: each full product resized to m_prod_w with numeric_std
// semantics, then bits m_prod_w-1 .. m_drop kept (drop m_drop LSBs: floor(x / 2^m_drop)).
// Template over the number type T (Word or LeanWord).
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

template <class T>
struct MProductsT {
    T a, b, c;
};
using MProducts = MProductsT<Word>;

template <class T>
inline T m_product(const T& x, const T& y, const Formats& f) {
    const T full = resize(x * y, f.m_prod_w);        // 2*sobel_w -> m_prod_w bits (thesis 22 -> 21: +-1020^2 fits)
    return slice(full, f.m_prod_w - 1, f.m_drop);   // drop m_drop LSBs: m_prod_w -> m_w() bits
}

template <class T>
inline MProductsT<T> m_products(const T& ix, const T& iy, const Formats& f) {
    return {m_product(ix, ix, f), m_product(ix, iy, f), m_product(iy, iy, f)};
}

}  // namespace hc
