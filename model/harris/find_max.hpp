// find_max.hpp: model of rtl/find_max.vhd.
//
// On each enabled step the centre response updates the running maximum; after
// find_max_period enabled steps the running maximum is published and restarts from the
// most negative value (the response of the step that ends a period is not counted).
// Only `max` is reset.
// Template over the number type T of the response (Word, or LeanWord in the cycle model's
// format-specialised instances); FindMax is the Word instance. The step itself,
// find_max_step, also runs on the stage proofs' symbolic word (sweep/stage_equivalence.hpp).
#pragma once

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

/// find_max's registers after one enabled step.
template <class T, class C>
struct FindMaxStep {
    C count;
    T running, max;
};

/// One enabled step on the registers (count, running, max) and the centre response;
/// `period`: find_max_period. C is the counter's type: long, or the stage proofs' symbolic
/// word (sweep/smt_word.hpp), as T may be; the choices are written with choose() so both run.
template <class T, class C>
FindMaxStep<T, C> find_max_step(const C& count, const T& running, const T& max, const T& response, long period) {
    const auto counting = count < constant_like(count, period);
    const C one = constant_like(count, 1);
    const T updated = choose(response > running, response, running);
    return {choose(counting, count + one, one),
            choose(counting, updated, T::most_negative(running.width())),   // the restart overrides the update
            choose(counting, max, running)};
}

/// find_max's registers. C is the counter's type: long, or the whole-design proof's symbolic
/// word (sweep/datapath_induction.cpp), which gives the counter's first value.
template <class T, class C = long>
struct FindMaxT {
    C count;
    T running;
    T max;

    explicit FindMaxT(const Formats& f, const C& count0 = C(1))
        : count(count0), running(T::most_negative(f.resp_w)), max(T::most_negative(f.resp_w)) {}

    void reset(const Formats& f) { max = T::most_negative(f.resp_w); }

    FindMaxT next(const T& response, const Geometry& g) const {
        const FindMaxStep<T, C> s = find_max_step(count, running, max, response, g.find_max_period());
        FindMaxT n = *this;
        n.count = s.count;
        n.running = s.running;
        n.max = s.max;
        return n;
    }
};
using FindMax = FindMaxT<Word>;

}  // namespace hc
