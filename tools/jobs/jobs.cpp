// jobs.cpp: the registry of job kinds.
#include "tools/jobs/jobs.hpp"

namespace hc::jobs {

const cluster::JobRegistry& registry() {
    static const cluster::JobRegistry reg = [] {
        cluster::JobRegistry r;
        eval::add_eval_job(r);
        vl::add_verilate_job(r);
        sweep::add_sweep_job(r);
        sweep::add_sweep_check_job(r);
        mutation::add_mutate_job(r);
        landmarks::add_landmarks_job(r);
        slam::add_slam_job(r);
        mutation::add_mutants_job(r);
        return r;
    }();
    return reg;
}

}  // namespace hc::jobs
