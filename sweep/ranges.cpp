// ranges.cpp: see ranges.hpp.
#include "sweep/ranges.hpp"

#include <cctype>
#include <chrono>
#include <functional>
#include <random>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "model/fixed/word.hpp"
#include "model/harris/block_filter.hpp"
#include "model/harris/formats_json.hpp"
#include "model/harris/harris_response.hpp"
#include "model/harris/m_products.hpp"
#include "model/harris/sobel_x.hpp"
#include "model/harris/sobel_y.hpp"
#include "model/harris/threshold.hpp"
#include "util/util.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace hc::sweep {

namespace {

// Bump when the analysis (bounds, search, verdicts) changes: cached reports then miss.
constexpr const char* kRangesVersion = "hc-ranges-1 interval + witness search";

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int idx(Reg r) { return static_cast<int>(r); }

/// Runs one stage on RangeWord twice: keeping ideal values past every narrowing (the bound
/// of the register's exact value and whether every narrowing fits it), then as the hardware
/// (the register as the next stage sees it: its whole range when it may wrap).
struct IntervalPass {
    RangeReport& rep;
    RangeWord stage(Reg r, const std::function<RangeWord()>& fn) {
        RangeLog ideal;
        ideal.keep_ideal = true;
        RangeWord exact;
        {
            RangeScope scope(ideal);
            exact = fn();
        }
        RegisterRange& rr = rep.regs[idx(r)];
        rr.bound = exact.ideal;
        rr.width = exact.w;
        rr.held = representable(exact.w, exact.s);
        rr.bound_fits = ideal.events.empty() && exact.exact();
        rr.verdict = rr.bound_fits ? Verdict::proven : Verdict::open;
        RangeLog hw;
        RangeWord out;
        {
            RangeScope scope(hw);
            out = fn();
        }
        return RangeWord::materialised(out);
    }
};

/// Nine independent values (the nine positions of a block) of one register's range.
std::array<std::array<RangeWord, 3>, 3> nine(const RangeWord& m) {
    std::array<std::array<RangeWord, 3>, 3> a;
    for (auto& row : a)
        for (auto& x : row) x = RangeWord::fresh(m.ideal, m.w, m.s);
    return a;
}

Pixels3 pixels_at(const Window5& w, int i, int j) {
    Pixels3 nb;
    for (int di = 0; di < 3; ++di)
        for (int dj = 0; dj < 3; ++dj) nb[di][dj] = static_cast<Pixel>(w[i + di][j + dj]);
    return nb;
}

json interval_json(const Interval& v) { return json::array({v.lo, v.hi}); }
Interval interval_from(const json& j) { return {j.at(0).get<std::int64_t>(), j.at(1).get<std::int64_t>()}; }

}  // namespace

Stage audit_stage(Reg r) {
    switch (r) {
        case Reg::sobel_x: case Reg::sobel_y: return sobel;
        case Reg::m_a: case Reg::m_b: case Reg::m_c: return m_resize;
        case Reg::block_a: case Reg::block_b: case Reg::block_c: return block_sum;
        case Reg::k_term: return k_term;
        case Reg::det: case Reg::response: case Reg::maximum: return response;
        default: return stage_count;
    }
}

const char* verdict_name(Verdict v) {
    return v == Verdict::proven ? "proven" : v == Verdict::wraps ? "wraps" : "open";
}

Verdict RangeReport::overall() const {
    bool open = false;
    for (const auto& r : regs) {
        if (r.verdict == Verdict::wraps) return Verdict::wraps;
        open = open || r.verdict == Verdict::open;
    }
    return open ? Verdict::open : Verdict::proven;
}

const RegisterRange* RangeReport::first_wrap() const {
    for (const auto& r : regs)
        if (r.verdict == Verdict::wraps) return &r;
    return nullptr;
}

std::string RangeReport::summary() const {
    switch (overall()) {
        case Verdict::proven: return "proven safe";
        case Verdict::wraps: return std::string("wraps at ") + kRegNames[idx(first_wrap()->reg)];
        default: break;
    }
    std::string s;
    for (const auto& r : regs)
        if (r.verdict == Verdict::open)
            s += fmt::format("{}{}: bound [{}, {}] in [{}, {}]{}", s.empty() ? "" : "; ", kRegNames[idx(r.reg)], r.bound.lo,
                             r.bound.hi, r.held.lo, r.held.hi,
                             r.searched ? fmt::format(", reached [{}, {}]", r.reached.lo, r.reached.hi) : "");
    return "open (" + s + ")";
}

RangeReport interval_ranges(const Formats& f, int pixel_max) {
    f.validate();
    const auto t0 = Clock::now();
    RangeReport rep;
    rep.formats = f;
    rep.pixel_max = pixel_max;
    rep.regs.resize(kRegCount);
    for (int i = 0; i < kRegCount; ++i) rep.regs[i].reg = static_cast<Reg>(i);
    IntervalPass pass{rep};
    using R = RangeWord;
    std::array<std::array<Interval, 3>, 3> px;
    for (auto& row : px) row.fill(Interval{0, pixel_max});
    const R ix = pass.stage(Reg::sobel_x, [&] { return sobel_x<R>(px, f); });
    const R iy = pass.stage(Reg::sobel_y, [&] { return sobel_y<R>(px, f); });
    const R ma = pass.stage(Reg::m_a, [&] { return m_product(ix, ix, f); });
    const R mb = pass.stage(Reg::m_b, [&] { return m_product(ix, iy, f); });
    const R mc = pass.stage(Reg::m_c, [&] { return m_product(iy, iy, f); });
    const R a = pass.stage(Reg::block_a, [&] { return block_filter(nine(ma), f); });
    const R b = pass.stage(Reg::block_b, [&] { return block_filter(nine(mb), f); });
    const R c = pass.stage(Reg::block_c, [&] { return block_filter(nine(mc), f); });
    pass.stage(Reg::trace, [&] { return harris_trace(a, c, f); });
    ResponseTermsT<R> t;
    t.ktr2 = pass.stage(Reg::k_term, [&] {
        t = harris_response_terms(a, b, c, f);
        return t.ktr2;
    });
    // det: a*c and b*b are exact products; the response resizes each to resp_w
    {
        RegisterRange& d = rep.regs[idx(Reg::det)];
        d.bound = {t.ac.ideal.lo - t.bb.ideal.hi, t.ac.ideal.hi - t.bb.ideal.lo};
        d.width = f.resp_w;
        d.held = representable(f.resp_w, true);
        d.bound_fits = fits(t.ac.ideal, f.resp_w, true) && fits(t.bb.ideal, f.resp_w, true);
        d.verdict = d.bound_fits ? Verdict::proven : Verdict::open;
    }
    const R r = pass.stage(Reg::response, [&] { return harris_response(t, f); });
    // the maximum is a response or the reset value (most negative); it wraps iff a response does
    {
        RegisterRange& m = rep.regs[idx(Reg::maximum)];
        m.bound = hull(r.held(), {representable(f.resp_w, true).lo, representable(f.resp_w, true).lo});
        m.width = f.resp_w;
        m.held = representable(f.resp_w, true);
        m.bound_fits = rep.regs[idx(Reg::response)].bound_fits;
        m.verdict = m.bound_fits ? Verdict::proven : Verdict::open;
    }
    const R mx = R::fresh(rep.regs[idx(Reg::maximum)].bound, f.resp_w, true);
    pass.stage(Reg::threshold, [&] { return threshold_value(mx, f); });
    rep.seconds_interval = since(t0);
    return rep;
}

std::array<WindowValue, kRegCount> window_values(const Window5& w, const Formats& f, bool maximise) {
    std::array<WindowValue, kRegCount> v{};
    const auto better = [&](std::int64_t x, std::int64_t y) { return maximise ? x > y : x < y; };
    const auto keep = [&](Reg r, std::int64_t exact, std::int64_t narrowed, bool first) {
        WindowValue& o = v[idx(r)];
        if (first || better(exact, o.exact) || (exact == o.exact && narrowed != exact)) o = {exact, narrowed};
    };
    std::array<std::array<Word, 3>, 3> A, B, C;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const Pixels3 nb = pixels_at(w, i, j);
            const int gx = (nb[0][2] + 2 * nb[1][2] + nb[2][2]) - (nb[0][0] + 2 * nb[1][0] + nb[2][0]);
            const int gy = (nb[0][0] + 2 * nb[0][1] + nb[0][2]) - (nb[2][0] + 2 * nb[2][1] + nb[2][2]);
            const Word ix = sobel_x<Word>(nb, f), iy = sobel_y<Word>(nb, f);
            const bool first = i == 0 && j == 0;
            keep(Reg::sobel_x, gx, ix.value(), first);
            keep(Reg::sobel_y, gy, iy.value(), first);
            const MProducts m = m_products(ix, iy, f);
            // the M register against floor(exact product / 2^m_drop): equal iff the resize kept the product
            keep(Reg::m_a, (ix.value() * ix.value()) >> f.m_drop, m.a.value(), first);
            keep(Reg::m_b, (ix.value() * iy.value()) >> f.m_drop, m.b.value(), first);
            keep(Reg::m_c, (iy.value() * iy.value()) >> f.m_drop, m.c.value(), first);
            A[i][j] = m.a;
            B[i][j] = m.b;
            C[i][j] = m.c;
        }
    const auto block = [&](Reg r, const std::array<std::array<Word, 3>, 3>& M) {
        std::int64_t sum = 0;
        for (const auto& row : M)
            for (const auto& x : row) sum += x.value();
        const Word out = block_filter(M, f);
        v[idx(r)] = {sum >> f.bf_drop, out.value()};
        return out;
    };
    const Word a = block(Reg::block_a, A), b = block(Reg::block_b, B), c = block(Reg::block_c, C);
    const Word tr = harris_trace(a, c, f);
    v[idx(Reg::trace)] = {a.value() + c.value(), tr.value()};
    const ResponseTerms t = harris_response_terms(a, b, c, f);
    const std::int64_t tr2 = (a.value() + c.value()) * (a.value() + c.value());
    v[idx(Reg::k_term)] = {(tr2 >> f.k_shift1) + (tr2 >> f.k_shift2), t.ktr2.value()};
    v[idx(Reg::det)] = {t.ac.value() - t.bb.value(),
                        resize(t.ac, f.resp_w).value() - resize(t.bb, f.resp_w).value()};
    const Word r = harris_response(t, f);
    v[idx(Reg::response)] = {t.ac.value() - t.bb.value() - t.ktr2.value(), r.value()};
    v[idx(Reg::maximum)] = v[idx(Reg::response)];
    v[idx(Reg::threshold)] = {(r.value() >> f.thr_shift1) + (r.value() >> f.thr_shift2), threshold_value(r, f).value()};
    return v;
}

Image witness_image(const Window5& w, int width, int height) {
    if (width < 10 || height < 8) throw std::invalid_argument("witness_image: at least 10x8");
    Image im(width, height);
    const int y0 = (height - 5) / 2, x0 = (width - 5) / 2;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            im.at(y, x) = static_cast<std::uint8_t>(w[std::clamp(y - y0, 0, 4)][std::clamp(x - x0, 0, 4)]);
    return im;
}

std::string witness_stem(const std::string& config, Reg r) {
    std::string s = config + "_" + kRegNames[idx(r)];
    for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '-';
    return s;
}

std::string ranges_markdown(const std::string& config, const RangeReport& r) {
    std::string s = fmt::format("### {}: {}\n\nInterval bound {:.3f} ms, witness search {:.3f} s{}; pixels in [0, {}].\n\n", config,
                                r.summary(), 1e3 * r.seconds_interval, r.seconds_search, r.cached ? " (cached)" : "", r.pixel_max);
    s += "| register | width | holds | bound (any input) | verdict | search reached | witness |\n|---|---:|---|---|---|---|---|\n";
    for (const auto& x : r.regs) {
        std::string wit;
        if (x.verdict == Verdict::wraps) {
            for (const auto& row : x.witness) {
                wit += wit.empty() ? "" : " / ";
                for (size_t j = 0; j < row.size(); ++j) wit += fmt::format("{}{}", j ? " " : "", row[j]);
            }
        }
        s += fmt::format("| {} | {} | [{}, {}] | [{}, {}] | {} | {} | {} |\n", kRegNames[idx(x.reg)], x.width, x.held.lo, x.held.hi,
                         x.bound.lo, x.bound.hi, x.verdict == Verdict::wraps ? "**wraps**" : verdict_name(x.verdict),
                         x.searched ? fmt::format("[{}, {}]", x.reached.lo, x.reached.hi) : "-", wit);
    }
    return s;
}

std::string WitnessFile::regression_line(const fs::path& set_dir) const {
    return fmt::format("{}  16x12  2  0  breaks={}", fs::relative(image, set_dir).generic_string(),
                       fs::relative(formats, set_dir).generic_string());
}

std::vector<WitnessFile> write_witnesses(const std::string& config, const RangeReport& r, const fs::path& dir) {
    std::vector<WitnessFile> out;
    std::string slug = config;
    for (char& ch : slug)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '-';
    for (const auto& x : r.regs) {
        if (x.verdict != Verdict::wraps || x.reg == Reg::maximum) continue;   // the maximum's window is the response's
        WitnessFile w;
        w.reg = x.reg;
        w.image = dir / (witness_stem(config, x.reg) + ".pgm");
        w.formats = dir / (slug + ".json");
        util::write_file_atomic(w.image, pgm_bytes(witness_image(x.witness)));
        util::write_file_atomic(w.formats, formats_to_json(r.formats, config));
        out.push_back(w);
    }
    return out;
}

namespace {

/// Coordinate ascent on one register's exact value from structured and random seeds, until
/// a window wraps it, the seeds are spent or the time is up.
void search_witness(RegisterRange& rr, const Formats& f, const RangeOptions& o, bool maximise) {
    const auto t0 = Clock::now();
    const int pm = o.pixel_max;
    const auto score = [&](const Window5& w, bool& wraps) {
        const WindowValue x = window_values(w, f, maximise)[idx(rr.reg)];
        wraps = x.exact != x.narrowed;
        rr.reached = rr.searched ? hull(rr.reached, {x.exact, x.exact}) : Interval{x.exact, x.exact};
        rr.searched = true;
        return maximise ? x.exact : -x.exact;
    };
    std::vector<Window5> seeds;
    const auto add = [&](const std::function<bool(int, int)>& on) {
        Window5 w{};
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j) w[i][j] = on(i, j) ? pm : 0;
        seeds.push_back(w);
    };
    for (int m = 0; m < 32; ++m) {
        add([m](int, int j) { return (m >> j) & 1; });   // column stripes
        add([m](int i, int) { return (m >> i) & 1; });   // row stripes
    }
    for (int m = 0; m < 512; ++m) {
        add([m](int i, int j) { return (m >> (i + j)) & 1; });       // diagonals
        add([m](int i, int j) { return (m >> (i - j + 4)) & 1; });   // anti-diagonals
    }
    // the best structured seeds first, then random vertices
    std::vector<std::pair<std::int64_t, size_t>> ranked;
    for (size_t k = 0; k < seeds.size(); ++k) {
        bool wraps = false;
        const std::int64_t s = score(seeds[k], wraps);
        if (wraps) {
            rr.verdict = Verdict::wraps;
            rr.witness = seeds[k];
            return;
        }
        ranked.emplace_back(-s, k);
    }
    std::sort(ranked.begin(), ranked.end());
    std::vector<Window5> starts;
    for (size_t k = 0; k < std::min<size_t>(16, ranked.size()); ++k) starts.push_back(seeds[ranked[k].second]);
    std::mt19937 rng(12345);
    for (int k = 0; k < o.seeds; ++k) {
        Window5 w{};
        for (auto& row : w)
            for (auto& p : row) p = (rng() & 1) ? pm : 0;
        starts.push_back(w);
    }
    const std::array<int, 5> levels{0, pm / 4, pm / 2, pm - pm / 4, pm};
    for (Window5 w : starts) {
        bool wraps = false;
        std::int64_t best = score(w, wraps);
        for (bool improved = true; improved && !wraps;) {
            improved = false;
            for (int i = 0; i < 5 && !wraps; ++i)
                for (int j = 0; j < 5 && !wraps; ++j)
                    for (int lv : levels) {
                        if (lv == w[i][j]) continue;
                        const int was = w[i][j];
                        w[i][j] = lv;
                        const std::int64_t s = score(w, wraps);
                        if (wraps) break;
                        if (s > best) {
                            best = s;
                            improved = true;
                        } else {
                            w[i][j] = was;
                        }
                    }
        }
        if (wraps) {
            rr.verdict = Verdict::wraps;
            rr.witness = w;
            return;
        }
        if (since(t0) > o.search_seconds) return;
    }
}

}  // namespace

RangeReport analyse_ranges(const Formats& f, const RangeOptions& o) {
    RangeReport rep = interval_ranges(f, o.pixel_max);
    const auto t0 = Clock::now();
    for (auto& rr : rep.regs) {
        if (rr.bound_fits) continue;
        // the side(s) of the bound that leave the register; both when a narrowing inside the stage may wrap
        const bool hi = rr.bound.hi > rr.held.hi, lo = rr.bound.lo < rr.held.lo;
        if (hi || !lo) search_witness(rr, f, o, true);
        if (rr.verdict != Verdict::wraps && (lo || !hi)) search_witness(rr, f, o, false);
    }
    // the maximum holds a response: it wraps with the response's witness
    RegisterRange& m = rep.regs[idx(Reg::maximum)];
    const RegisterRange& r = rep.regs[idx(Reg::response)];
    if (!m.bound_fits && r.verdict == Verdict::wraps) {
        m.verdict = Verdict::wraps;
        m.witness = r.witness;
    }
    rep.seconds_search = since(t0);
    return rep;
}

json range_report_to_json(const RangeReport& r) {
    json regs = json::array();
    for (const auto& x : r.regs) {
        json e = {{"register", kRegNames[idx(x.reg)]}, {"bound", interval_json(x.bound)}, {"held", interval_json(x.held)},
                  {"width", x.width}, {"bound_fits", x.bound_fits}, {"verdict", verdict_name(x.verdict)},
                  {"searched", x.searched}};
        if (x.searched) e["reached"] = interval_json(x.reached);
        if (x.verdict == Verdict::wraps) e["witness"] = x.witness;
        regs.push_back(e);
    }
    return {{"flow", kRangesVersion}, {"formats", fields_text(r.formats, format_fields())}, {"pixel_max", r.pixel_max},
            {"key", r.key}, {"verdict", verdict_name(r.overall())}, {"summary", r.summary()},
            {"seconds_interval", r.seconds_interval}, {"seconds_search", r.seconds_search}, {"registers", regs}};
}

RangeReport range_report_from_json(const json& j) {
    RangeReport r;
    if (j.at("flow").get<std::string>() != kRangesVersion) throw std::invalid_argument("range report of another analysis version");
    r.pixel_max = j.at("pixel_max");
    r.key = j.at("key");
    r.seconds_interval = j.at("seconds_interval");
    r.seconds_search = j.at("seconds_search");
    const json& regs = j.at("registers");
    if (regs.size() != static_cast<size_t>(kRegCount)) throw std::invalid_argument("range report: wrong register count");
    for (int i = 0; i < kRegCount; ++i) {
        const json& e = regs.at(i);
        if (e.at("register").get<std::string>() != kRegNames[i]) throw std::invalid_argument("range report: registers out of order");
        RegisterRange x;
        x.reg = static_cast<Reg>(i);
        x.bound = interval_from(e.at("bound"));
        x.held = interval_from(e.at("held"));
        x.width = e.at("width");
        x.bound_fits = e.at("bound_fits");
        const std::string v = e.at("verdict");
        x.verdict = v == "proven" ? Verdict::proven : v == "wraps" ? Verdict::wraps : Verdict::open;
        if (v != verdict_name(x.verdict)) throw std::invalid_argument("range report: verdict '" + v + "'");
        x.searched = e.at("searched");
        if (x.searched) x.reached = interval_from(e.at("reached"));
        if (x.verdict == Verdict::wraps) x.witness = e.at("witness").get<Window5>();
        r.regs.push_back(x);
    }
    return r;
}

RangeReport cached_ranges(const Formats& f, const std::string& key, const fs::path& cache_dir, const RangeOptions& o) {
    const fs::path p = cache_dir / (key + ".json");
    if (fs::exists(p)) {
        try {
            RangeReport r = range_report_from_json(json::parse(util::read_file(p)));
            if (r.pixel_max == o.pixel_max) {
                r.formats = f;
                r.cached = true;
                return r;
            }
        } catch (const std::exception&) {
            // another version or an unreadable entry: analyse again and overwrite it
        }
    }
    RangeReport r = analyse_ranges(f, o);
    r.key = key;
    fs::create_directories(cache_dir);
    util::write_file_atomic(p, range_report_to_json(r).dump(1) + "\n");
    return r;
}

}  // namespace hc::sweep
