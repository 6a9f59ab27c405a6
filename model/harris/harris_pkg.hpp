// harris_pkg.hpp: the formats and geometry of the co-processor, mirroring rtl/harris_pkg.vhd.
//
// Purpose: one struct holds every width, dropped-bit count and constant shift, with the
// thesis's values as defaults (Schulz 2015, appendix A and D). The RTL takes the same values
// as generics of harris_top; generics() lists them under the VHDL names, so a configuration
// drives both sides from one place.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace hc {

/// Bit widths and constant shifts of the datapath.
struct Formats {
    int sobel_w = 11;     ///< Sobel x/y output, signed (range +-1020 needs 11)
    int m_prod_w = 21;    ///< M products resized to this width ...
    int m_drop = 5;       ///< ... then this many LSBs dropped (21 -> 16: floor(/32))
    int bf_sum_w = 20;    ///< block-filter accumulator width ...
    int bf_drop = 4;      ///< ... then this many LSBs dropped (20 -> 16: floor(/16))
    int resp_w = 32;      ///< response, maximum and threshold width
    int ktr_w = 30;       ///< k*tr^2 width
    int k_shift1 = 5;     ///< k = 2^-k_shift1 + 2^-k_shift2 = 1/32 + 1/128
    int k_shift2 = 7;
    int thr_shift1 = 7;   ///< thr = max * (2^-thr_shift1 + 2^-thr_shift2) = max*(1/128+1/512)
    int thr_shift2 = 9;

    // derived widths: do not set
    int m_w() const { return m_prod_w - m_drop; }        ///< M coefficient width
    int bf_w() const { return bf_sum_w - bf_drop; }      ///< block-sum width
    int prod_w() const { return 2 * bf_w(); }            ///< a*c, b*b in the response
    int trace_w() const { return bf_w() + 1; }           ///< a + c
    int trace_sq_w() const { return 2 * trace_w(); }     ///< (a + c)^2

    /// Throws std::invalid_argument naming the first field that cannot be built.
    void validate() const;
    friend bool operator==(const Formats&, const Formats&) = default;
};

/// Image size the counters of the design are built for.
struct Geometry {
    int width = 640;
    int height = 360;

    int rows() const { return height / 2 - 3; }              ///< window rows per frame
    int columns() const { return width / 2 + 3; }            ///< window columns per row
    int row_writes() const { return columns() * 7; }         ///< writes per window row
    long frame_writes() const { return static_cast<long>(rows()) * row_writes(); }
    int di() const { return height / 2 - 3; }                ///< quadrant row offset
    int dj() const { return width / 2 - 3; }                 ///< quadrant column offset
    /// find-max period: (h/2-3)*(w/2+3)*4 enabled steps
    long find_max_period() const { return static_cast<long>(rows()) * columns() * 4; }

    /// Smallest size the design and the host driver can cover: one row of windows
    /// (h/2-3 >= 1) and one processed window column after the 7-column fill (w/2+3 >= 8).
    static constexpr int min_width = 10;
    static constexpr int min_height = 8;
    /// Throws std::invalid_argument when the design cannot be built for this size.
    void validate() const;
    friend bool operator==(const Geometry&, const Geometry&) = default;
};

/// The generics of harris_top for a geometry and formats, as (VHDL name, value).
std::vector<std::pair<std::string, long>> generics(const Geometry& g, const Formats& f);

}  // namespace hc
