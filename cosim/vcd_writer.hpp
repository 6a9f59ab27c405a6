// vcd_writer.hpp: a VCD file of the cycles around a mismatch, RTL and model side by side.
//
// Each cycle is 10 ns. Scope `rtl` holds the observation port as the RTL drove it (with 'x'
// and 'z' for metavalues), scope `model` the cycle model's values, scope `cosim` the write
// index and a flag on cycles with a mismatch. GTKWave opens it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cosim/compare.hpp"

namespace hc::cosim {

struct CycleRecord {
    long write = 0;
    bool idle = false;
    bool mismatch = false;
    std::vector<std::uint8_t> rtl;       ///< observation codes
    FlatObservation model;
};

/// Writes the records as a VCD file. Throws std::runtime_error when the file cannot be written.
void write_vcd(const std::string& path, const ObsComparator& cmp, const std::vector<CycleRecord>& cycles);

}  // namespace hc::cosim
