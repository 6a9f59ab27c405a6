// observation.hpp: the inter-stage registers of harris_top, and their packing on the RTL's
// observation port (mirror of the `pack` process in rtl/harris_top.vhd).
//
// Fields are listed in pipeline order; a matrix is row-major from (1,1); each element's bits
// go most significant first. obs_layout() is the one description both the encoder (model
// side) and the decoder (RTL side) use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/harris/harris_pkg.hpp"
#include "model/harris/types.hpp"

namespace hc {

/// Every register harris_top exposes, as the model holds them after a write.
struct Observation {
    bool load = true;
    bool ready = false;
    std::uint8_t t = 0;
    Window7 icm{};
    bool icm_defined = false;
    Matrix5 sx, sy, ma, mb, mc;
    Matrix3 bfa, bfb, bfc, hr;
    Word max, thr;
    Matrix3 tr;
    bool cornerbit = false;
    std::uint8_t corner_sr = 0;
    std::uint32_t corner = 0;
};

/// One field of the observation port.
struct ObsField {
    std::string name;    ///< signal name in harris_top
    std::string stage;   ///< entity that drives it
    int rows;            ///< 1 for a scalar
    int cols;
    int width;           ///< bits per element
    bool is_signed;
    int elements() const { return rows * cols; }
};

/// Pipeline order of the stages, used to name the first mismatching stage.
const std::vector<std::string>& stage_order();

std::vector<ObsField> obs_layout(const Formats& f);
/// Total bits of the observation port (rtl harris_pkg.obs_width).
int obs_width(const Formats& f);

/// Element values (bit patterns) in layout order. `defined[k]` is false for an element the
/// design holds as 'U' (the window register before the first write).
struct FlatObservation {
    std::vector<std::uint64_t> bits;
    std::vector<bool> defined;
};
FlatObservation flatten(const Observation& o, const Formats& f);

}  // namespace hc
