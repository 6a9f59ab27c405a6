// sweep_config.hpp: what a bit-width sweep explores, read from one JSON spec file.
//
// Purpose: a configuration is a named hc::Formats (model/harris/harris_pkg.hpp); the same
// value drives the spec model (accuracy, overflow audit), the synthesis (generics of
// harris_top) and the RTL runs (`harris-cosim rtl/verilate --config`), so a point of the
// sweep cannot mean different widths on different sides.
//
// Spec file (JSON object; every key optional except that some configuration must result):
//   {
//     "name":    "widths",                        label of the sweep (reports)
//     "base":    {"resp_w": 32},                  Formats keys applied under every entry
//     "configs": [ {"name": "thesis"},            explicit points: Formats keys (+ "name")
//                  {"name": "narrow-sobel", "sobel_w": 10} ],
//     "grid":    {"m_drop": [5, 6, 7], "bf_drop": [4, 5]}   cartesian product over base;
//                                                  or a list of such objects
//     "cost":    {"img_width": 640, "img_height": 360}      generics for synthesis
//     "trust":   {"rtl": true, "verilator_pairs": "0:5", "verilator_gate": true}
//     "data":    {"sequence": "01", "pairs": "0:51"}
//     "landmarks": {"scenes": ["Aloe", "Rocks1"], "g": 16, "h": 3}   or false
//   }
// Unspecified Formats keys keep the thesis's values. The thesis configuration is always
// part of the sweep (added as "thesis" when no entry equals it): it is the yardstick of
// the findings. Entries with equal Formats are merged (first name kept).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"

namespace hc::sweep {

/// One point of the sweep.
struct Config {
    std::string name;   ///< unique within the sweep; grid points: "m_drop=6,bf_drop=5"
    Formats formats;
};

struct TrustOptions {
    bool rtl = true;                  ///< GHDL co-simulation of the regression set per Pareto point
    std::string verilator_pairs = "0:5";   ///< KITTI stereo pairs for `verilate` ("" = skip)
    bool verilator_gate = true;       ///< run verilate's three-way gate (else --no-gate)
};

/// The downstream column: correct stereo matches of the landmark chain (spec-model corners,
/// grid descriptor (g, h), appendix F matching) on a few Middlebury 2006 half-size scenes,
/// scored by landmarks::score_formats.
struct LandmarkSpec {
    bool enabled = true;
    std::vector<std::string> scenes{"Aloe", "Rocks1"};   ///< folders under middlebury2006/half
    int g = 16, h = 3;                                   ///< the thesis's Harris choice
};

/// The trajectory column: visual odometry and EKF-SLAM on a KITTI sequence's stereo pairs from
/// the spec model's corners of each configuration (slam::run_kitti_sequence with its defaults
/// and `descriptor`); the sequence's poses only score. Off unless the spec asks for it.
struct TrajectorySpec {
    bool enabled = false;
    std::string sequence = "01";
    std::string descriptor = "orb";   ///< a binary descriptor of landmarks::parse_descriptor
};

struct SweepSpec {
    std::string name = "sweep";
    std::vector<Config> configs;      ///< in file order: configs, then grid points, then thesis
    Geometry cost_geometry{};         ///< IMG_WIDTH/IMG_HEIGHT of the synthesised design
    TrustOptions trust;
    std::string sequence = "01";      ///< KITTI sequence
    std::string pairs;                ///< "a:b" stereo pairs ("" = all)
    LandmarkSpec landmarks;
    TrajectorySpec trajectory;
    std::vector<std::string> notes;   ///< merged duplicates etc., for the report
};

/// Parses a spec from JSON text; `what` names the input in errors (e.g. the file path).
/// Throws InputError with a message that names `what` and the offending entry.
SweepSpec parse_sweep_spec(const std::string& text, const std::string& what);
/// Reads and parses a spec file (errors name the path).
SweepSpec load_sweep_spec(const std::filesystem::path& p);

// A configuration's name where none is given: describe_difference() (harris_pkg.hpp); its
// JSON: formats_to_json() (model/harris/formats_json.hpp).

}  // namespace hc::sweep
