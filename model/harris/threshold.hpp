// threshold.hpp: model of rtl/threshold.vhd and of the threshold value formed in harris_top.
//
// thr = resize(max(top downto thr_shift1)) + resize(max(top downto thr_shift2)) in resp_w
// bits: floor(max / 2^thr_shift1) + floor(max / 2^thr_shift2) (thesis: floor(max/128) +
// floor(max/512), about 0.00977*max; OpenCV uses 0.01*max of
// the current frame; the hardware uses the maximum of the previous find-max period).
// A response below thr becomes 0; one equal to thr is kept.
// Templates over the number type T (Word or LeanWord; threshold also on the stage proofs'
// symbolic word, sweep/smt_word.hpp).
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

template <class T>
inline T threshold_value(const T& max, const Formats& f) {
    const int top = f.resp_w - 1;
    return resize(slice(max, top, f.thr_shift1), f.resp_w) +   // floor(max / 2^thr_shift1)
           resize(slice(max, top, f.thr_shift2), f.resp_w);    // + floor(max / 2^thr_shift2)
}

template <class T>
inline T threshold(const T& r, const T& thr) {
    return choose(r >= thr, r, T::sgn(0, r.width()));
}

}  // namespace hc
