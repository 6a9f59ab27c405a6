#include "cosim/vcd_writer.hpp"

#include <fstream>
#include <stdexcept>

namespace hc::cosim {

namespace {
std::string vcd_id(int n) {
    std::string s;
    do {
        s.push_back(static_cast<char>(33 + n % 94));
        n /= 94;
    } while (n > 0);
    return s;
}
char vcd_char(std::uint8_t code) {
    switch (code) {
        case SL_0: return '0';
        case SL_1: return '1';
        case SL_Z: return 'z';
        default: return 'x';
    }
}
std::string var_name(const ObsComparator& cmp, int e) {
    const int fld = cmp.element_field(e);
    const ObsField& f = cmp.layout()[fld];
    int idx = 0;
    for (int k = e - 1; k >= 0 && cmp.element_field(k) == fld; --k) ++idx;
    if (f.rows == 1 && f.cols == 1) return f.name;
    return f.name + "_" + std::to_string(idx / f.cols + 1) + "_" + std::to_string(idx % f.cols + 1);
}
}  // namespace

void write_vcd(const std::string& path, const ObsComparator& cmp, const std::vector<CycleRecord>& cycles) {
    std::ofstream o(path);
    if (!o) throw std::runtime_error("cannot write VCD '" + path + "'");
    const int n = cmp.elements();
    o << "$comment harris-cosim: cycles around the first mismatch, RTL vs cycle model $end\n";
    o << "$timescale 1ns $end\n";
    o << "$scope module cosim $end\n";
    o << "$var integer 32 " << vcd_id(0) << " write_index $end\n";
    o << "$var wire 1 " << vcd_id(1) << " mismatch $end\n";
    o << "$var wire 1 " << vcd_id(2) << " idle $end\n";
    o << "$upscope $end\n";
    for (int side = 0; side < 2; ++side) {
        o << "$scope module " << (side == 0 ? "rtl" : "model") << " $end\n";
        for (int e = 0; e < n; ++e) {
            const int w = cmp.layout()[cmp.element_field(e)].width;
            o << "$var wire " << w << " " << vcd_id(3 + side * n + e) << " " << var_name(cmp, e)
              << (w > 1 ? " [" + std::to_string(w - 1) + ":0]" : "") << " $end\n";
        }
        o << "$upscope $end\n";
    }
    o << "$enddefinitions $end\n";
    long t = 0;
    for (const auto& c : cycles) {
        o << "#" << t << "\n";
        std::string wbits;
        for (int b = 31; b >= 0; --b) wbits.push_back(((static_cast<unsigned long>(c.write) >> b) & 1U) ? '1' : '0');
        o << "b" << wbits << " " << vcd_id(0) << "\n";
        o << (c.mismatch ? '1' : '0') << vcd_id(1) << "\n";
        o << (c.idle ? '1' : '0') << vcd_id(2) << "\n";
        for (int e = 0; e < n; ++e) {
            const int w = cmp.layout()[cmp.element_field(e)].width;
            const int off = cmp.element_offset(e);
            std::string r, m;
            for (int b = 0; b < w; ++b) {
                r.push_back(vcd_char(c.rtl[off + b]));
                const bool def = c.model.defined[e];
                m.push_back(!def ? 'x' : (((c.model.bits[e] >> (w - 1 - b)) & 1U) ? '1' : '0'));
            }
            if (w == 1) {
                o << r << vcd_id(3 + e) << "\n" << m << vcd_id(3 + n + e) << "\n";
            } else {
                o << "b" << r << " " << vcd_id(3 + e) << "\nb" << m << " " << vcd_id(3 + n + e) << "\n";
            }
        }
        t += 10;
    }
    o << "#" << t << "\n";
    if (!o) throw std::runtime_error("cannot write VCD '" + path + "'");
}

}  // namespace hc::cosim
