// registry.cpp: the registry of every job kind (registry.hpp).
#include "tools/registry.hpp"

#include "cosim/verilator/verilate_job.hpp"
#include "eval/eval_job.hpp"
#include "mutation/mutate_generated_job.hpp"
#include "mutation/mutate_job.hpp"
#include "mapping/landmarks/landmarks_job.hpp"
#include "mapping/slam/slam_job.hpp"
#include "sweep/sweep_job.hpp"

namespace hc::tools {

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
        mutation::add_mutate_generated_job(r);
        return r;
    }();
    return reg;
}

}  // namespace hc::tools
