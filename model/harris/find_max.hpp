// find_max.hpp: model of rtl/find_max.vhd.
//
// On each enabled step the centre response updates the running maximum; after
// find_max_period enabled steps the running maximum is published and restarts from the
// most negative value (the response of the step that ends a period is not counted).
// Only `max` is reset.
// Template over the number type T of the response (Word, or LeanWord in the cycle model's
// format-specialised instances); FindMax is the Word instance.
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

template <class T>
struct FindMaxT {
    long count = 1;
    T running;
    T max;

    explicit FindMaxT(const Formats& f)
        : running(T::most_negative(f.resp_w)), max(T::most_negative(f.resp_w)) {}

    void reset(const Formats& f) { max = T::most_negative(f.resp_w); }

    FindMaxT next(const T& response, const Geometry& g) const {
        FindMaxT n = *this;
        if (response > running) n.running = response;
        if (count < g.find_max_period()) {
            n.count = count + 1;
        } else {
            n.count = 1;
            n.running = T::most_negative(running.width());   // overrides the update
            n.max = running;
        }
        return n;
    }
};
using FindMax = FindMaxT<Word>;

}  // namespace hc
