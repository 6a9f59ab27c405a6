// session.hpp: one co-simulation run on the C++ side of the bridge.
//
// The session owns the frames, the host driver model (which decides every bus cycle), the
// cycle model (stepped on every write before the RTL's clock edge) and the comparator that
// checks the RTL's observation port after the edge. It keeps the last cycles for a VCD,
// counts mismatches per stage, records every read and writes a JSON summary at the end.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cosim/compare.hpp"
#include "model/driver/host_driver.hpp"
#include "model/harris/harris_top.hpp"
#include "cosim/run_config.hpp"
#include "cosim/vcd_writer.hpp"

namespace hc::cosim {

enum class Command { write, idle, end };

class Session {
public:
    explicit Session(RunConfig cfg);

    /// Checks the testbench's observation width and generics against the configuration;
    /// throws std::invalid_argument describing the first difference.
    void check_design(int obs_w, const std::vector<long>& generic_values) const;

    Command next();
    std::uint32_t data() const { return ev_.data; }
    /// The observation port after the cycle's rising edge. Returns true to stop the simulation.
    bool observe(const std::uint8_t* codes);
    /// The observation port while the clock is low (after reset before the first edge, or
    /// between two edges): registers change only on a rising edge, so the port must hold
    /// the model's state after the last write; a difference is a mismatch reported with
    /// when it was seen. Returns true to stop the simulation.
    bool observe_held(const std::uint8_t* codes, bool after_reset);
    /// Writes the VCD (if any mismatch) and the summary; returns 0 pass, 1 mismatch.
    int close();

    /// The one-screen report of the first mismatch ("" if none).
    const std::string& first_report() const { return first_report_; }

private:
    /// When the port was observed.
    enum class Phase { after_edge, after_reset, clock_low };
    std::string describe(const std::vector<Mismatch>& ms, long write, std::string& signal) const;
    /// Records the mismatches in scratch_ of an observation `codes` of the model's `flat`.
    bool record(const std::uint8_t* codes, FlatObservation& flat);
    void progress(bool final);
    void record_read(const std::uint8_t* codes);

    RunConfig cfg_;
    std::vector<Image> frames_;
    std::unique_ptr<HostDriver> driver_;
    std::unique_ptr<HarrisTop> model_;
    ObsComparator cmp_;
    BusEvent ev_;
    bool idle_now_ = false;
    Phase phase_ = Phase::after_edge;
    int since_idle_ = 0;
    long cycles_ = 0;
    long idles_ = 0;
    long reads_ = 0;
    long read_mismatches_ = 0;
    std::vector<long> corners_per_frame_;
    std::deque<std::pair<long, WritePos>> positions_;   // recent writes' positions
    std::deque<CycleRecord> history_;
    std::vector<CycleRecord> vcd_cycles_;
    bool vcd_done_ = false;
    int post_left_ = -1;                                // cycles still to record after the first mismatch
    bool stop_ = false;
    long mismatching_cycles_ = 0;
    long mismatched_elements_ = 0;
    long metavalue_elements_ = 0;
    std::map<std::string, long> stage_cycles_;          // cycles where the stage mismatched
    std::map<std::string, long> stage_elements_;        // elements that mismatched
    std::map<std::string, long> first_stage_cycles_;    // cycles where it was the first stage
    std::string first_report_;
    std::string first_stage_;
    std::string first_signal_;
    long first_write_ = 0;
    std::ofstream reads_out_;
    std::chrono::steady_clock::time_point start_, last_progress_;
    std::vector<Mismatch> scratch_;
};

}  // namespace hc::cosim
