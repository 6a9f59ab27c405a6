// jobs.cpp: the registry of job kinds.
#include "tools/jobs/jobs.hpp"

#include <cmath>
#include <limits>

namespace hc::jobs {

const cluster::JobRegistry& registry() {
    static const cluster::JobRegistry reg = [] {
        cluster::JobRegistry r;
        add_eval_job(r);
        add_verilate_job(r);
        r.add(detail::sweep_job());
        r.add(detail::sweep_check_job());
        r.add(detail::mutate_job());
        r.add(detail::landmarks_job());
        r.add(detail::slam_job());
        add_mutants_job(r);
        return r;
    }();
    return reg;
}

namespace detail {

json doubles(const std::vector<double>& v) {
    json a = json::array();
    for (double x : v) a.push_back(std::isnan(x) ? json(nullptr) : json(x));
    return a;
}

std::vector<double> doubles(const json& j) {
    std::vector<double> v;
    for (const auto& x : j) v.push_back(x.is_null() ? std::numeric_limits<double>::quiet_NaN() : x.get<double>());
    return v;
}

}  // namespace detail

}  // namespace hc::jobs
