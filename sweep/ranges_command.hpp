// ranges_command.hpp: `harris-cosim ranges` as the command line hands it over: the derived
// range of every datapath register of one configuration or of every configuration of a
// sweep spec (ranges.hpp), as Markdown, JSON and witness stimuli.
#pragma once

#include <string>
#include <vector>

#include "sweep/ranges.hpp"

namespace hc::sweep {

/// The command's settings, one field per flag.
struct RangesCommand {
    std::string config, spec, witnesses, set_dir, json, out;
    int pixel_max = 255;
    RangeOptions ro;   ///< the solver limits (--search-windows, --solver-rlimit, ...)
    bool no_netlist = false;
    std::string netlist_dir;
    std::string stages;   ///< --stages DIR: stage equivalence too, its netlists and queries kept under DIR/<config>/<stage>
    std::string rtl;      ///< --rtl DIR: the VHDL the stage proofs synthesise (empty: the project's rtl/)
    /// --control-induction DIR: the control registers of the whole design's netlist from reset
    /// (control_induction.hpp), at each of `control_sizes`, kept under DIR/<config>/<WxH>
    std::string control_induction;
    /// --datapath-induction DIR: every register of the whole design's netlist from reset
    /// (datapath_induction.hpp), at each of `control_sizes`, kept under DIR/<config>/<WxH>
    std::string datapath_induction;
    std::vector<std::string> control_sizes{"10x8"};   ///< --control-sizes WxH,...
    std::string propose;  ///< --propose FILE: the narrowest proven widths (propose_widths) as a --config file
};

/// Analyses every configuration, writes --json, --out (else prints the Markdown) and the
/// witnesses, and prints each witness's regression-set line; with --propose (one configuration),
/// adds the proposed widths to the report and writes them as a --config file, atomically, once
/// every report is made. InputError for bad input.
void run_ranges_command(const RangesCommand& c);

}  // namespace hc::sweep
