// find_max.hpp: model of rtl/find_max.vhd.
//
// On each enabled step the centre response updates the running maximum; after
// find_max_period enabled steps the running maximum is published and restarts from the
// most negative value (the response of the step that ends a period is not counted).
// Only `max` is reset.
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

struct FindMax {
    long count = 1;
    Word running;
    Word max;

    explicit FindMax(const Formats& f)
        : running(Word::most_negative(f.resp_w)), max(Word::most_negative(f.resp_w)) {}

    void reset(const Formats& f) { max = Word::most_negative(f.resp_w); }

    FindMax next(const Word& response, const Geometry& g) const {
        FindMax n = *this;
        if (response > running) n.running = response;
        if (count < g.find_max_period()) {
            n.count = count + 1;
        } else {
            n.count = 1;
            n.running = Word::most_negative(running.width());   // overrides the update
            n.max = running;
        }
        return n;
    }
};

}  // namespace hc
