#include "model/harris/harris_pkg.hpp"

#include <stdexcept>
#include <string>

#include "model/fixed/word.hpp"
#include "model/util/util.hpp"

namespace hc {

namespace {
void need(bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("invalid formats: " + what);
}
}  // namespace

void Formats::validate() const {
    need(sobel_w >= 2 && sobel_w <= 30, "sobel_w must be 2..30");
    need(m_prod_w >= 2 && m_prod_w <= Word::max_width, "m_prod_w must be 2..62");
    need(m_drop >= 0 && m_drop < m_prod_w, "m_drop must be 0..m_prod_w-1");
    need(bf_sum_w >= 2 && bf_sum_w <= 40, "bf_sum_w must be 2..40");
    need(bf_drop >= 0 && bf_drop < bf_sum_w, "bf_drop must be 0..bf_sum_w-1");
    need(trace_sq_w() <= Word::max_width, "bf_sum_w - bf_drop too wide for (a+c)^2");
    need(resp_w >= 2 && resp_w <= Word::max_width, "resp_w must be 2..62");
    need(ktr_w >= 1 && ktr_w <= Word::max_width, "ktr_w must be 1..62");
    need(k_shift1 >= 0 && k_shift1 < trace_sq_w(), "k_shift1 must be below the (a+c)^2 width");
    need(k_shift2 >= 0 && k_shift2 < trace_sq_w(), "k_shift2 must be below the (a+c)^2 width");
    need(thr_shift1 >= 0 && thr_shift1 < resp_w, "thr_shift1 must be below resp_w");
    need(thr_shift2 >= 0 && thr_shift2 < resp_w, "thr_shift2 must be below resp_w");
}

void Geometry::validate() const {
    if (width < min_width || height < min_height)
        throw std::invalid_argument("image " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is smaller than the design's minimum " +
                                    std::to_string(min_width) + "x" + std::to_string(min_height));
    if (width > 1 << 15 || height > 1 << 15)
        throw std::invalid_argument("image " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is larger than 32768 on a side");
}

std::uint64_t formats_hash(const Formats& f) { return util::fnv1a(fields_text(f, format_fields())); }

}  // namespace hc
