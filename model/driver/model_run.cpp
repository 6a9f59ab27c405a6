// model_run.cpp: see model_run.hpp.
#include "model/driver/model_run.hpp"

#include <chrono>
#include <numeric>
#include <sstream>

#include "model/driver/bus_loop.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"

namespace hc {

long ModelRun::corners() const { return std::accumulate(corners_per_frame.begin(), corners_per_frame.end(), 0L); }

ModelRun run_cycle_model(const std::vector<Image>& frames, const Formats& f, bool record_reads) {
    const Geometry g{frames.at(0).width, frames.at(0).height};
    std::vector<const Image*> ptrs;
    for (const auto& im : frames) ptrs.push_back(&im);
    HostDriver drv(g, ptrs);
    HarrisTop top(g, f);
    ModelRun run;
    run.corners_per_frame.assign(frames.size(), 0);
    std::ostringstream reads;
    if (record_reads) reads << "write,frame,x,y,value\n";
    struct Hooks : BusHooks {
        ModelRun& run;
        const HarrisTop& top;
        std::ostringstream* reads;   // null unless every read is listed
        void read(const BusEvent& ev, std::uint32_t value, const std::vector<Corner>& cs) {
            ++run.reads;
            run.corners_per_frame[ev.read->frame] += static_cast<long>(cs.size());
            if (reads)
                *reads << top.writes() << ',' << ev.read->frame << ',' << ev.read->x << ',' << ev.read->y << ',' << value
                       << '\n';
        }
    } hooks{{}, run, top, record_reads ? &reads : nullptr};
    const auto t0 = std::chrono::steady_clock::now();
    BusLoop loop(drv, top);
    loop.run(hooks);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    run.writes = top.writes();
    run.reads_csv = reads.str();
    return run;
}

}  // namespace hc
