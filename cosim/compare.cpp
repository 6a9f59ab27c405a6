#include "cosim/compare.hpp"

#include <algorithm>
#include <cstdio>

namespace hc::cosim {

char std_logic_char(std::uint8_t code) {
    static const char chars[] = "UX01ZWLH-";
    return code <= SL_DC ? chars[code] : '?';
}

ObsComparator::ObsComparator(const Formats& f) : layout_(obs_layout(f)) {
    const auto& order = stage_order();
    for (size_t k = 0; k < layout_.size(); ++k) {
        const auto it = std::find(order.begin(), order.end(), layout_[k].stage);
        stage_of_field_.push_back(static_cast<int>(it - order.begin()));
        for (int e = 0; e < layout_[k].elements(); ++e) {
            offsets_.push_back(width_);
            element_field_.push_back(static_cast<int>(k));
            element_index_.push_back(e);
            width_ += layout_[k].width;
            ++elements_;
        }
    }
}

void ObsComparator::compare(const std::uint8_t* codes, const FlatObservation& model, long write,
                            std::vector<Mismatch>& out) const {
    for (int e = 0; e < elements_; ++e) {
        const int fld = element_field_[e];
        const int w = layout_[fld].width;
        const std::uint8_t* c = codes + offsets_[e];
        std::uint64_t bits = 0;
        bool meta = false, all_u = true;
        for (int b = 0; b < w; ++b) {
            const std::uint8_t code = c[b];
            all_u = all_u && code == SL_U;
            if (code == SL_1) bits |= std::uint64_t{1} << (w - 1 - b);
            else if (code != SL_0) meta = true;
        }
        const bool defined = model.defined[e];
        bool bad;
        if (!defined) bad = !all_u;                 // the model says 'U': the RTL must too
        else bad = meta || bits != model.bits[e];
        if (!bad) continue;
        const int idx = element_index_[e];
        Mismatch m;
        m.write = write;
        m.field = fld;
        m.i = idx / layout_[fld].cols + 1;
        m.j = idx % layout_[fld].cols + 1;
        m.expected = model.bits[e];
        m.actual = element_chars(codes, e);
        m.metavalue = defined && meta;
        m.model_undefined = !defined;
        out.push_back(std::move(m));
    }
}

std::string ObsComparator::element_chars(const std::uint8_t* codes, int element) const {
    const int w = layout_[element_field_[element]].width;
    std::string s(static_cast<size_t>(w), '?');
    for (int b = 0; b < w; ++b) s[b] = std_logic_char(codes[offsets_[element] + b]);
    return s;
}

std::string ObsComparator::element_name(int field, int i, int j) const {
    const ObsField& f = layout_[field];
    if (f.rows == 1 && f.cols == 1) return f.name;
    return f.name + "(" + std::to_string(i) + "," + std::to_string(j) + ")";
}

std::string ObsComparator::format_value(int field, std::uint64_t bits) const {
    const ObsField& f = layout_[field];
    const Word w = Word::from_bits(bits, f.width, f.is_signed);
    char buf[64];
    std::snprintf(buf, sizeof buf, "%lld (0x%0*llx)", static_cast<long long>(w.value()), (f.width + 3) / 4,
                  static_cast<unsigned long long>(bits));
    return buf;
}

}  // namespace hc::cosim
