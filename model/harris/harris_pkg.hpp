// harris_pkg.hpp: the formats and geometry of the co-processor, mirroring rtl/harris_pkg.vhd.
//
// Purpose: one struct holds every width, dropped-bit count and constant shift, with the
// thesis's values as defaults (Schulz 2015, appendix A and D). The table beside it,
// format_fields(), names each field once: its C++/JSON name, its VHDL generic, its VHDL
// subtype and what it means. Every list of fields is derived from that table: the JSON of
// `--config` and of sweep specs (model/harris/formats_json.hpp), the generics handed to GHDL
// and Verilator (generics()), cache keys (formats_hash()), error messages and tests. The
// VHDL defaults (DEF_* in rtl/harris_pkg.vhd) are checked against it by a test.
//
// Adding a field: a member of Formats with its default, a row of format_fields(), the
// generic in rtl/ (harris_pkg.vhd DEF_*, the entities that use it); docs/architecture.md.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace hc {

/// Bit widths and constant shifts of the datapath.
struct Formats {
    // The defaults are the thesis's; format_fields() says what each one means.
    int sobel_w = 11;
    int m_prod_w = 21;
    int m_drop = 5;
    int bf_sum_w = 20;
    int bf_drop = 4;
    int resp_w = 32;
    int ktr_w = 30;
    int k_shift1 = 5;
    int k_shift2 = 7;
    int thr_shift1 = 7;
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

/// One field of a formats struct S: its names on both sides, what it means, and where it
/// lives. A template so that a test can extend the table (a struct derived from Formats
/// with one more field) and show that everything derived from it follows.
template <class S>
struct FieldOf {
    const char* name;        ///< C++ member and JSON key
    const char* generic;     ///< VHDL generic of harris_top (default DEF_<generic> in harris_pkg.vhd)
    const char* vhdl_type;   ///< VHDL subtype of the generic: "positive" or "natural"
    const char* meaning;     ///< one line, in terms of the other fields
    int S::*member;
    int default_value() const { return S{}.*member; }
};
using FormatField = FieldOf<Formats>;

/// Every field of Formats, in struct order (the order of the VHDL generics).
inline constexpr std::array<FormatField, 11> kFormatFields{{
    {"sobel_w", "SOBEL_W", "positive", "Sobel x/y output width, signed", &Formats::sobel_w},
    {"m_prod_w", "M_PROD_W", "positive", "width the M products (ix*ix, ix*iy, iy*iy) are resized to", &Formats::m_prod_w},
    {"m_drop", "M_DROP", "natural", "LSBs dropped from an M product: M = floor(p / 2^m_drop), m_prod_w - m_drop bits", &Formats::m_drop},
    {"bf_sum_w", "BF_SUM_W", "positive", "width of the block filter's 3x3 sum", &Formats::bf_sum_w},
    {"bf_drop", "BF_DROP", "natural", "LSBs dropped from the block sum: floor(sum / 2^bf_drop), bf_sum_w - bf_drop bits", &Formats::bf_drop},
    {"resp_w", "RESP_W", "positive", "width of the response, the maximum and the threshold", &Formats::resp_w},
    {"ktr_w", "KTR_W", "positive", "width the k*(a+c)^2 term is held in", &Formats::ktr_w},
    {"k_shift1", "K_SHIFT1", "natural", "k = 2^-k_shift1 + 2^-k_shift2 (first shift)", &Formats::k_shift1},
    {"k_shift2", "K_SHIFT2", "natural", "k = 2^-k_shift1 + 2^-k_shift2 (second shift)", &Formats::k_shift2},
    {"thr_shift1", "THR_SHIFT1", "natural", "threshold = max * (2^-thr_shift1 + 2^-thr_shift2) (first shift)", &Formats::thr_shift1},
    {"thr_shift2", "THR_SHIFT2", "natural", "threshold = max * (2^-thr_shift1 + 2^-thr_shift2) (second shift)", &Formats::thr_shift2},
}};
inline const auto& format_fields() { return kFormatFields; }

/// The generics of harris_top for a geometry and a formats struct described by `table`:
/// IMG_WIDTH, IMG_HEIGHT, then one per table row, as (VHDL name, value).
template <class S, std::size_t N>
std::vector<std::pair<std::string, long>> generics_of(const Geometry& g, const S& f,
                                                      const std::array<FieldOf<S>, N>& table) {
    std::vector<std::pair<std::string, long>> v = {{"IMG_WIDTH", g.width}, {"IMG_HEIGHT", g.height}};
    for (const auto& fld : table) v.emplace_back(fld.generic, f.*(fld.member));
    return v;
}
/// The generics of harris_top for a geometry and formats, as (VHDL name, value).
inline std::vector<std::pair<std::string, long>> generics(const Geometry& g, const Formats& f) {
    return generics_of(g, f, format_fields());
}

/// "name=value,name=value..." over every row of `table`: the text a cache key hashes, so a
/// new row can never share a key with a configuration that lacks it.
template <class S, std::size_t N>
std::string fields_text(const S& f, const std::array<FieldOf<S>, N>& table) {
    std::string s;
    for (const auto& fld : table) {
        if (!s.empty()) s += ',';
        s.append(fld.name).append("=").append(std::to_string(f.*(fld.member)));
    }
    return s;
}
/// The fields of `table` where `f` differs from the defaults ("sobel_w=10,m_drop=6"), or
/// "thesis" when none does.
template <class S, std::size_t N>
std::string describe_difference_of(const S& f, const std::array<FieldOf<S>, N>& table) {
    std::string s;
    for (const auto& fld : table)
        if (f.*(fld.member) != fld.default_value()) {
            if (!s.empty()) s += ',';
            s.append(fld.name).append("=").append(std::to_string(f.*(fld.member)));
        }
    return s.empty() ? "thesis" : s;
}
inline std::string describe_difference(const Formats& f) { return describe_difference_of(f, format_fields()); }

/// A 64-bit hash of every field (FNV-1a of fields_text): part of every cache key that
/// depends on the formats (netlists, gate passes, synthesis, RTL checks).
std::uint64_t formats_hash(const Formats& f);

}  // namespace hc
