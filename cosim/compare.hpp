// compare.hpp: decoding the RTL's observation port and comparing it with the cycle model.
//
// The port arrives as std_ulogic codes, one byte per bit (0 'U', 1 'X', 2 '0', 3 '1',
// 4 'Z', 5 'W', 6 'L', 7 'H', 8 '-'). Only '0' and '1' are values: every other code makes
// the element a metavalue mismatch, its own failure class, never read as 0.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "model/harris/observation.hpp"

namespace hc::cosim {

/// std_ulogic codes as GHDL passes them.
enum : std::uint8_t { SL_U = 0, SL_X, SL_0, SL_1, SL_Z, SL_W, SL_L, SL_H, SL_DC };
char std_logic_char(std::uint8_t code);

struct Mismatch {
    long write = 0;            ///< write index (from 1); idle cycles carry the last write's
    int field = 0;             ///< index in obs_layout
    int i = 0, j = 0;          ///< matrix index from 1 (1,1 for scalars)
    std::uint64_t expected = 0;    ///< model bits
    std::string actual;        ///< RTL bits, MSB first, as std_logic characters
    bool metavalue = false;    ///< the RTL element holds a non-0/1 bit
    bool model_undefined = false;  ///< the model holds 'U' here and the RTL does not
};

class ObsComparator {
public:
    explicit ObsComparator(const Formats& f);

    const std::vector<ObsField>& layout() const { return layout_; }
    int width() const { return width_; }
    /// Elements compared on every cycle (each matrix element and scalar counts once).
    int elements() const { return elements_; }
    /// Index of a field's stage in stage_order().
    int stage_index(int field) const { return stage_of_field_[field]; }

    /// Appends every element where `codes` (width() bytes) differs from the model.
    void compare(const std::uint8_t* codes, const FlatObservation& model, long write,
                 std::vector<Mismatch>& out) const;

    /// Element k's bits from the codes, MSB first as characters.
    std::string element_chars(const std::uint8_t* codes, int element) const;
    /// Bit offset of element k in the port.
    int element_offset(int element) const { return offsets_[element]; }
    int element_field(int element) const { return element_field_[element]; }
    /// "mbm(3,2)" or "max".
    std::string element_name(int field, int i, int j) const;
    /// A value as signed or unsigned decimal plus hex, per the field's type.
    std::string format_value(int field, std::uint64_t bits) const;

private:
    std::vector<ObsField> layout_;
    std::vector<int> stage_of_field_;
    std::vector<int> offsets_;        // per element
    std::vector<int> element_field_;  // per element
    std::vector<int> element_index_;  // per element: row-major index within its field
    int width_ = 0;
    int elements_ = 0;
};

}  // namespace hc::cosim
