// pareto.hpp: Pareto-optimal selection over objectives to be minimised.
//
// A point p dominates q when p is no worse than q in every objective and strictly better
// in at least one. The front is every eligible point no eligible point dominates; points
// equal in every objective are all kept. (Maximised figures such as F1 enter negated.)
#pragma once

#include <vector>

namespace hc::sweep {

inline bool dominates(const std::vector<double>& p, const std::vector<double>& q) {
    bool strictly = false;
    for (size_t k = 0; k < p.size(); ++k) {
        if (p[k] > q[k]) return false;
        if (p[k] < q[k]) strictly = true;
    }
    return strictly;
}

/// front[i] is true when point i is eligible and no eligible point dominates it.
/// `objectives[i]` are point i's values, all of one length; `eligible` empty = all.
inline std::vector<bool> pareto_front(const std::vector<std::vector<double>>& objectives,
                                      const std::vector<bool>& eligible = {}) {
    const size_t n = objectives.size();
    auto ok = [&](size_t i) { return eligible.empty() || eligible[i]; };
    std::vector<bool> front(n, false);
    for (size_t i = 0; i < n; ++i) {
        if (!ok(i)) continue;
        bool dominated = false;
        for (size_t j = 0; j < n && !dominated; ++j) dominated = j != i && ok(j) && dominates(objectives[j], objectives[i]);
        front[i] = !dominated;
    }
    return front;
}

}  // namespace hc::sweep
