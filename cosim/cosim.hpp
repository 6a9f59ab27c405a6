// cosim.hpp: the GHDL co-simulation as a C++ call. run_ghdl() streams frames through the
// elaborated testbench cosim/harris_top_tb.vhd (a child process: the GHDL simulator, with
// the bridge library cosim/hc_bridge.h inside it comparing every cycle with the cycle
// model) and returns what the run found as a typed Summary (cosim/run_config.hpp).
//
// Errors: InputError (unknown or unbuilt back end, unwritable outputs), SimulatorError
// (the simulator did not start, stopped without a summary, or is older than an RTL file it
// was built from). A mismatch is not an exception: it is in the Summary.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cosim/run_config.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"

namespace hc::cosim {

/// One co-simulation run.
struct GhdlRun {
    std::vector<Image> frames;             ///< one size; chained when more than one
    std::vector<std::string> frame_names;
    Formats formats;
    std::string backend = "gcc";           ///< gcc, llvm or mcode
    bool keep_going = false;               ///< count every mismatch instead of stopping
    bool compare_all = true;               ///< every register after every cycle; false: reads only
    int idle_every = 0;                    ///< an idle cycle after every N writes
    long max_writes = 0;                   ///< stop after N writes (0: the whole stream)
    bool progress = true;                  ///< progress lines on stderr
    // outputs, moved into place after the run (empty: not written)
    std::filesystem::path summary_json;    ///< the summary as JSON
    std::filesystem::path vcd;             ///< VCD around the first mismatch (only if there is one)
    std::filesystem::path wave;            ///< GHW waveform of the whole run
    std::filesystem::path reads_csv;       ///< every read: write,frame,x,y,value
    /// The simulators: the build's (empty), or a directory prepared by analyse_mcode().
    std::filesystem::path sim_dir;
    std::filesystem::path log;             ///< the simulator's output (empty: this process's)
};

struct GhdlResult {
    Summary summary;
    int simulator_status = 0;              ///< the child's exit status (0 pass, 1 mismatch)
    std::filesystem::path reads_csv;       ///< where the reads went (run.reads_csv), if asked
};

/// Runs the co-simulation. See the header comment for the errors.
GhdlResult run_ghdl(const GhdlRun& run);

/// The GHDL back ends this build has a simulator for (configure time), e.g. {"gcc", "mcode"}.
std::vector<std::string> ghdl_backends();

/// The RTL files of the design in analysis order (a package, then each entity after the
/// ones it instantiates), in `rtl_dir` (empty: the source tree's rtl/).
std::vector<std::filesystem::path> rtl_sources(const std::filesystem::path& rtl_dir = {});
/// The source tree's rtl/ directory.
std::filesystem::path rtl_dir();

/// Analyses the VHDL of `rtl_dir` (rtl_sources order) with the bridge package and the
/// testbench for GHDL's mcode back end into `sim_dir`, which then serves as
/// GhdlRun::sim_dir with backend "mcode"; its analysis stamp (sim_dir/ghdl-mcode/
/// analysed.stamp) dates it, so run_ghdl refuses it, as it refuses the build's, once a
/// file of the source tree's rtl/ is newer. Returns false when the analysis fails (its
/// messages go to `log`). Throws SimulatorError when ghdl-mcode is not installed.
bool analyse_mcode(const std::filesystem::path& rtl_dir, const std::filesystem::path& sim_dir,
                   const std::filesystem::path& log);

}  // namespace hc::cosim
