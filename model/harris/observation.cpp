#include "model/harris/observation.hpp"

namespace hc {

const std::vector<std::string>& stage_order() {
    static const std::vector<std::string> order = {
        "load_control", "input_converter_mux", "control_shift_register", "sobel_x", "sobel_y",
        "m_products",   "block_filter",        "harris_response",        "find_max",
        "threshold",    "local_maximum",       "corner_shift_register",  "harris_top"};
    return order;
}

std::vector<ObsField> obs_layout(const Formats& f) {
    return {
        {"load", "load_control", 1, 1, 1, false},
        {"ready", "input_converter_mux", 1, 1, 1, false},
        {"t", "control_shift_register", 1, 1, 6, false},
        {"icm", "input_converter_mux", 7, 7, 8, false},
        {"sxm", "sobel_x", 5, 5, f.sobel_w, true},
        {"sym", "sobel_y", 5, 5, f.sobel_w, true},
        {"mam", "m_products", 5, 5, f.m_w(), true},
        {"mbm", "m_products", 5, 5, f.m_w(), true},
        {"mcm", "m_products", 5, 5, f.m_w(), true},
        {"bfam", "block_filter", 3, 3, f.bf_w(), true},
        {"bfbm", "block_filter", 3, 3, f.bf_w(), true},
        {"bfcm", "block_filter", 3, 3, f.bf_w(), true},
        {"hrm", "harris_response", 3, 3, f.resp_w, true},
        {"max", "find_max", 1, 1, f.resp_w, true},
        {"thr", "threshold", 1, 1, f.resp_w, true},
        {"trm", "threshold", 3, 3, f.resp_w, true},
        {"cornerbit", "local_maximum", 1, 1, 1, false},
        {"corner_sr", "corner_shift_register", 1, 1, 4, false},
        {"corner", "harris_top", 1, 1, 32, false},
    };
}

int obs_width(const Formats& f) {
    int n = 0;
    for (const auto& fld : obs_layout(f)) n += fld.elements() * fld.width;
    return n;
}

FlatObservation flatten(const Observation& o, const Formats& f) {
    FlatObservation out;
    out.bits.reserve(256);
    auto put = [&](std::uint64_t b, bool def = true) {
        out.bits.push_back(b);
        out.defined.push_back(def);
    };
    auto put_m = [&](const auto& m) {
        for (const auto& row : m)
            for (const Word& w : row) put(w.bits());
    };
    put(o.load);
    put(o.ready);
    put(o.t);
    for (const auto& row : o.icm)
        for (Pixel p : row) put(p, o.icm_defined);
    put_m(o.sx);
    put_m(o.sy);
    put_m(o.ma);
    put_m(o.mb);
    put_m(o.mc);
    put_m(o.bfa);
    put_m(o.bfb);
    put_m(o.bfc);
    put_m(o.hr);
    put(o.max.bits());
    put(o.thr.bits());
    put_m(o.tr);
    put(o.cornerbit);
    put(o.corner_sr);
    put(o.corner);
    (void)f;
    return out;
}

}  // namespace hc
