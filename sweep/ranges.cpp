// ranges.cpp: see ranges.hpp.
#include "sweep/ranges.hpp"

#include <cctype>
#include <chrono>
#include <functional>
#include <cmath>
#include <map>
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
#include "model/util/util.hpp"
#include "sweep/smt_word.hpp"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace hc::sweep {

namespace {

// Bump when the analysis (bounds, search, verdicts) changes: cached reports then miss.
constexpr const char* kRangesVersion = "hc-ranges-5 interval + witness search + z3 (rlimit) on the model and on GHDL's netlist";

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr int idx(Reg r) { return static_cast<int>(r); }

/// Runs one stage on RangeWord twice: keeping ideal values past every narrowing (the bound
/// of the register's exact value and whether every narrowing fits it), then as the hardware
/// (the register as the next stage sees it: its whole range when it may wrap).
struct IntervalPass {
    RangeReport& rep;
    const Tightened* tight = nullptr;
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
        // a proven register with an exact range proven tighter: the next stage sees that
        if (tight && (*tight)[idx(r)] && rr.bound_fits) {
            const Interval t = *(*tight)[idx(r)];
            out.ideal = {std::max(out.ideal.lo, t.lo), std::min(out.ideal.hi, t.hi)};
            rr.bound = out.ideal;
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
Verdict verdict_from(const json& j) {
    const std::string v = j.get<std::string>();
    const Verdict x = v == "proven" ? Verdict::proven : v == "wraps" ? Verdict::wraps : Verdict::open;
    if (v != verdict_name(x)) throw std::invalid_argument("range report: verdict '" + v + "'");
    return x;
}
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
        case Verdict::wraps: {
            std::string s = std::string("wraps at ") + kRegNames[idx(first_wrap()->reg)], d;
            for (const auto& r : regs)
                if (r.netlist_differs) d += fmt::format("{}{}", d.empty() ? "" : ", ", kRegNames[idx(r.reg)]);
            return d.empty() ? s : s + "; the netlist differs from the VHDL at the witness of " + d;
        }
        default: break;
    }
    std::string s;
    for (const auto& r : regs)
        if (r.verdict == Verdict::open)
            s += fmt::format("{}{}: bound [{}, {}] in [{}, {}]{}{}", s.empty() ? "" : "; ", kRegNames[idx(r.reg)], r.bound.lo,
                             r.bound.hi, r.held.lo, r.held.hi,
                             r.searched ? fmt::format(", reached [{}, {}]", r.reached.lo, r.reached.hi) : "",
                             r.solver_asked ? ", solver: " + r.solver : "");
    return "open (" + s + ")";
}

std::string RangeReport::routes() const {
    std::string s;
    for (const char* route : {"interval", "search", "relation", "model-smt", "netlist"}) {
        const auto n = std::count_if(regs.begin(), regs.end(), [&](const RegisterRange& x) { return x.decided_by == route; });
        if (n) s += fmt::format("{}{} {}", s.empty() ? "" : ", ", route, n);
    }
    const auto open = std::count_if(regs.begin(), regs.end(), [](const RegisterRange& x) { return x.decided_by.empty(); });
    if (open) s += fmt::format("{}undecided {}", s.empty() ? "" : ", ", open);
    int asked = 0, by[3] = {0, 0, 0};
    for (const auto& x : regs)
        if (x.netlist_asked) {
            ++asked;
            ++by[static_cast<int>(x.netlist_verdict)];
        }
    if (!asked) return s + "; netlist not run";
    return s + fmt::format("; netlist: {} proven, {} wraps, {} open of {}", by[static_cast<int>(Verdict::proven)],
                           by[static_cast<int>(Verdict::wraps)], by[static_cast<int>(Verdict::open)], asked);
}

RangeReport interval_ranges(const Formats& f, int pixel_max, const Tightened* tight) {
    f.validate();
    const auto t0 = Clock::now();
    RangeReport rep;
    rep.formats = f;
    rep.pixel_max = pixel_max;
    rep.regs.resize(kRegCount);
    for (int i = 0; i < kRegCount; ++i) rep.regs[i].reg = static_cast<Reg>(i);
    IntervalPass pass{rep, tight};
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
    for (auto& x : rep.regs)
        if (x.bound_fits) x.decided_by = "interval";
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

std::string file_stem(const std::string& name) {
    std::string s = name;
    for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '_') ch = '-';
    return s;
}

std::string witness_stem(const std::string& config, Reg r) { return file_stem(config + "_" + kRegNames[idx(r)]); }

std::string ranges_markdown(const std::string& config, const RangeReport& r) {
    std::string s = fmt::format("### {}: {}\n\nInterval bound {:.3f} ms, witness search {:.3f} s, solver on the model {:.3f} s "
                                "({} z3 resource units{}), on the netlist {:.3f} s ({} units{}){}; pixels in [0, {}].\n\n",
                                config, r.summary(), 1e3 * r.seconds_interval, r.seconds_search, r.seconds_solver, r.solver_rlimit,
                                r.query_rlimit ? fmt::format(", at most {} per query", r.query_rlimit) : "", r.seconds_netlist,
                                r.netlist_rlimit,
                                r.netlist_query_rlimit ? fmt::format(", at most {} per query", r.netlist_query_rlimit) : "",
                                r.cached ? " (cached)" : "", r.pixel_max);
    if (!r.netlist_note.empty()) s += "Netlist: " + r.netlist_note + "\n\n";
    s += "| register | width | holds | bound (any input) | verdict | decided by | search reached | solver (model) | exact extreme | netlist | witness |\n"
         "|---|---:|---|---|---|---|---|---|---|---|---|\n";
    for (const auto& x : r.regs) {
        std::string wit;
        if (x.verdict == Verdict::wraps) {
            for (const auto& row : x.witness) {
                wit += wit.empty() ? "" : " / ";
                for (size_t j = 0; j < row.size(); ++j) wit += fmt::format("{}{}", j ? " " : "", row[j]);
            }
        }
        std::string extreme = "-";
        if (x.extreme_side) {
            const char* what = x.extreme_side > 0 ? "max" : "min";
            extreme = x.extreme.lo == x.extreme.hi ? fmt::format("{} = {}", what, x.extreme.lo)
                                                   : fmt::format("{} in [{}, {}]", what, x.extreme.lo, x.extreme.hi);
        }
        s += fmt::format("| {} | {} | [{}, {}] | [{}, {}] | {} | {} | {} | {} | {} | {} | {} |\n", kRegNames[idx(x.reg)], x.width,
                         x.held.lo, x.held.hi, x.bound.lo, x.bound.hi,
                         x.verdict == Verdict::wraps ? "**wraps**" : verdict_name(x.verdict), x.decided_by.empty() ? "-" : x.decided_by,
                         x.searched ? fmt::format("[{}, {}] ({} windows)", x.reached.lo, x.reached.hi, x.search_windows) : "-",
                         x.relation.empty() && !x.solver_asked ? "-"
                             : fmt::format("{}{}{}", x.relation.empty() ? "" : "relation " + x.relation,
                                           !x.relation.empty() && x.solver_asked ? "; " : "",
                                           x.solver_asked ? fmt::format("{} ({:.1f} s, {} units)", x.solver, x.solver_seconds,
                                                                        x.solver_rlimit)
                                                          : ""),
                         extreme,
                         x.netlist_asked ? fmt::format("{}{}: {} ({} units); {}", verdict_name(x.netlist_verdict),
                                                       x.netlist_differs ? ", **differs from the VHDL**" : "", x.netlist,
                                                       x.netlist_rlimit, x.netlist_vhdl)
                                         : "-",
                         wit);
    }
    return s;
}

std::string WitnessFile::regression_line(const fs::path& set_dir) const {
    return fmt::format("{}  16x12  2  0  breaks={}", fs::relative(image, set_dir).generic_string(),
                       fs::relative(formats, set_dir).generic_string());
}

std::vector<WitnessFile> write_witnesses(const std::string& config, const RangeReport& r, const fs::path& dir) {
    std::vector<WitnessFile> out;
    const std::string slug = file_stem(config);
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
/// a window wraps it, the seeds are spent or o.search_windows windows have been scored
/// (a count, not a time: two runs score the same windows and reach the same verdict).
void search_witness(RegisterRange& rr, const Formats& f, const RangeOptions& o, bool maximise) {
    const int pm = o.pixel_max;
    std::int64_t scored = 0;
    const auto spent = [&] { return scored >= o.search_windows; };
    const auto score = [&](const Window5& w, bool& wraps) {
        const WindowValue x = window_values(w, f, maximise)[idx(rr.reg)];
        ++scored;
        ++rr.search_windows;
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
    for (size_t k = 0; k < seeds.size() && !spent(); ++k) {
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
        if (spent()) return;
        bool wraps = false;
        std::int64_t best = score(w, wraps);
        for (bool improved = true; improved && !wraps && !spent();) {
            improved = false;
            for (int i = 0; i < 5 && !wraps; ++i)
                for (int j = 0; j < 5 && !wraps; ++j)
                    for (int lv : levels) {
                        if (lv == w[i][j] || spent()) continue;
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
    }
}

// ---- z3 ------------------------------------------------------------------------------

std::int64_t parse_bv(const std::string& s) {
    std::uint64_t v = 0;
    if (s.rfind("#x", 0) == 0) v = std::stoull(s.substr(2), nullptr, 16);
    else if (s.rfind("#b", 0) == 0) v = std::stoull(s.substr(2), nullptr, 2);
    else throw std::runtime_error("solver: unexpected value '" + s + "'");
    return static_cast<std::int64_t>(v);
}

}  // namespace

Z3Answer run_z3(const std::string& smt, std::int64_t rlimit, const std::vector<std::string>& get, const fs::path& keep) {
    std::string text = smt + "(check-sat)\n";
    if (!get.empty()) {
        text += "(get-value (";
        for (size_t k = 0; k < get.size(); ++k) text += (k ? " " : "") + get[k];
        text += "))\n";
    }
    text += "(get-info :rlimit)\n";
    const util::ScratchDir dir;
    const fs::path in = dir.path() / "query.smt2", out = dir.path() / "answer.txt";
    util::write_file_atomic(in, text);
    if (!keep.empty()) util::write_file_atomic(keep, text);
    Z3Answer a;
    const std::int64_t limit = std::max<std::int64_t>(1, rlimit);
    try {
        // z3 exits 1 after a get-value it cannot answer (unsat, unknown): the answer is read from its output
        util::run_process({"z3", "-smt2", fmt::format("rlimit={}", limit), in.string()}, {.log = dir.path() / "log", .stdout_file = out});
    } catch (const SimulatorError& e) {
        a.why = std::string("no solver: ") + e.what();
        return a;
    }
    const std::string ans = fs::exists(out) ? util::read_file(out) : "";
    const std::string first = ans.substr(0, ans.find('\n'));
    // an error before the answer is a malformed query: z3 goes on without what it could not read
    if (first.rfind("(error", 0) == 0) throw std::runtime_error("z3 could not read its query: " + first);
    if (const size_t r = ans.find("(:rlimit "); r != std::string::npos) a.rlimit = std::stoll(ans.substr(r + 9));
    if (first == "unsat") {
        a.sat = Sat::unsat;
        return a;
    }
    if (first != "sat") {
        a.why = first == "unknown" ? fmt::format("unknown: rlimit {} reached", limit)
                : first.empty()    ? "z3 gave no answer: " + util::log_tail(dir.path() / "log", 300)
                                   : "z3: " + first;
        return a;
    }
    // ((name #x...) (name #b...) ...)
    for (size_t k = ans.find('(', first.size()); k != std::string::npos; k = ans.find('(', k + 1)) {
        const size_t sp = ans.find(' ', k), close = ans.find(')', k);
        if (sp == std::string::npos || close == std::string::npos || sp > close) continue;
        const std::string name = ans.substr(k + 1, sp - k - 1), val = ans.substr(sp + 1, close - sp - 1);
        if (val.rfind("#", 0) == 0) a.values[name] = parse_bv(val);
    }
    for (const auto& g : get)
        if (!a.values.count(g)) throw std::runtime_error("z3 said sat without a value of " + g + ": " + ans.substr(0, 200));
    a.sat = Sat::sat;
    return a;
}

namespace {

// ---- the solver: the exact question as an SMT-LIB bit-vector query ----------------------

/// 64-bit integers (every exact value fits): the register's exact value beside its hardware value.
constexpr int kExactW = 64;
SmtWord wide(const SmtWord& x) { return extend(x, kExactW); }
SmtWord shr(const SmtWord& x, int n) {
    return n == 0 ? x : SmtWord::def(fmt::format("(bvashr {} (_ bv{} {}))", x.e, n, kExactW), kExactW, true);
}

/// The exact value and the hardware value of every register, as 64-bit terms of the 25
/// pixel variables p_<row>_<col> (Sobel and M: at the window's top-left 3x3 position; the
/// rest at its centre), defined by the stage functions on SmtWord as window_values does on Word.
struct SmtRegister {
    SmtWord exact, hw;
};
std::array<SmtRegister, kRegCount> smt_registers(const Formats& f) {
    std::array<SmtRegister, kRegCount> v;
    std::array<std::array<SmtWord, 5>, 5> px;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) px[i][j] = {fmt::format("p_{}_{}", i, j), 8, false};
    std::array<std::array<SmtWord, 3>, 3> A, B, C;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            std::array<std::array<SmtWord, 3>, 3> nb;
            for (int di = 0; di < 3; ++di)
                for (int dj = 0; dj < 3; ++dj) nb[di][dj] = px[i + di][j + dj];
            const SmtWord ix = sobel_x<SmtWord>(nb, f), iy = sobel_y<SmtWord>(nb, f);
            const MProductsT<SmtWord> m = m_products(ix, iy, f);
            if (i == 0 && j == 0) {
                const auto p = [&](int r, int c) { return wide(nb[r][c]); };
                const SmtWord two = SmtWord::constant(2, kExactW);
                const SmtWord gx = (p(0, 2) + two * p(1, 2) + p(2, 2)) - (p(0, 0) + two * p(1, 0) + p(2, 0));
                const SmtWord gy = (p(0, 0) + two * p(0, 1) + p(0, 2)) - (p(2, 0) + two * p(2, 1) + p(2, 2));
                v[idx(Reg::sobel_x)] = {resize(gx, kExactW), wide(ix)};
                v[idx(Reg::sobel_y)] = {resize(gy, kExactW), wide(iy)};
                v[idx(Reg::m_a)] = {shr(resize(wide(ix) * wide(ix), kExactW), f.m_drop), wide(m.a)};
                v[idx(Reg::m_b)] = {shr(resize(wide(ix) * wide(iy), kExactW), f.m_drop), wide(m.b)};
                v[idx(Reg::m_c)] = {shr(resize(wide(iy) * wide(iy), kExactW), f.m_drop), wide(m.c)};
            }
            A[i][j] = m.a;
            B[i][j] = m.b;
            C[i][j] = m.c;
        }
    const auto block = [&](Reg r, const std::array<std::array<SmtWord, 3>, 3>& M) {
        SmtWord sum = wide(M[0][0]);
        for (int k = 1; k < 9; ++k) sum = sum + wide(M[k / 3][k % 3]);
        const SmtWord out = block_filter(M, f);
        v[idx(r)] = {shr(sum, f.bf_drop), wide(out)};
        return out;
    };
    const SmtWord a = block(Reg::block_a, A), b = block(Reg::block_b, B), c = block(Reg::block_c, C);
    v[idx(Reg::trace)] = {wide(a) + wide(c), wide(harris_trace(a, c, f))};
    const ResponseTermsT<SmtWord> t = harris_response_terms(a, b, c, f);
    const SmtWord tr = wide(a) + wide(c), tr2 = resize(tr * tr, kExactW);
    v[idx(Reg::k_term)] = {shr(tr2, f.k_shift1) + shr(tr2, f.k_shift2), wide(t.ktr2)};
    v[idx(Reg::det)] = {wide(t.ac) - wide(t.bb), wide(resize(t.ac, f.resp_w)) - wide(resize(t.bb, f.resp_w))};
    const SmtWord r = harris_response(t, f);
    v[idx(Reg::response)] = {wide(t.ac) - wide(t.bb) - wide(t.ktr2), wide(r)};
    v[idx(Reg::maximum)] = v[idx(Reg::response)];
    v[idx(Reg::threshold)] = {shr(wide(r), f.thr_shift1) + shr(wide(r), f.thr_shift2), wide(threshold_value(r, f))};
    return v;
}

std::string bv64(std::int64_t v) { return fmt::format("(_ bv{} 64)", static_cast<std::uint64_t>(v)); }

struct SolverAnswer {
    Sat sat = Sat::unknown;
    Window5 window{};
    std::int64_t exact = 0;   ///< sat: the register's exact value at the window
    std::int64_t rlimit = 0;  ///< resource units spent
    std::string why;          ///< unknown: "rlimit N reached", "no solver", the solver's message
};

/// The names of a window's pixel functions p_<row>_<col>, row by row.
std::vector<std::string> pixel_names() {
    std::vector<std::string> v;
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) v.push_back(fmt::format("p_{}_{}", i, j));
    return v;
}

/// The window and the exact value of a sat answer whose values hold `exact` and the pixels.
SolverAnswer window_answer(const Z3Answer& z) {
    SolverAnswer a;
    a.sat = z.sat;
    a.rlimit = z.rlimit;
    a.why = z.why;
    if (z.sat != Sat::sat) return a;
    a.exact = z.values.at("exact");
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) a.window[i][j] = static_cast<int>(z.values.at(fmt::format("p_{}_{}", i, j)));
    return a;
}

/// Asks z3 whether a window of pixels in [0, pixel_max] satisfies `goal` (an SMT-LIB
/// condition on the terms `exact` and `hw` of register `reg`), within `rlimit` resource units.
SolverAnswer ask_solver(const Formats& f, Reg reg, int pixel_max, const std::string& goal, std::int64_t rlimit) {
    SmtQuery q;
    smt_query = &q;
    const std::array<SmtRegister, kRegCount> regs = smt_registers(f);
    smt_query = nullptr;
    std::string text = "(set-logic QF_BV)\n";
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j)
            text += fmt::format("(declare-const p_{0}_{1} (_ BitVec 8))\n(assert (bvule p_{0}_{1} (_ bv{2} 8)))\n", i, j, pixel_max);
    text += q.text;
    const SmtRegister& x = regs[idx(reg)];
    text += fmt::format("(define-fun exact () (_ BitVec 64) {})\n(define-fun hw () (_ BitVec 64) {})\n(assert {})\n",
                        x.exact.e, x.hw.e, goal);
    std::vector<std::string> get = pixel_names();
    get.push_back("exact");
    return window_answer(run_z3(text, rlimit, get));
}

/// The register's hardware value differs from its exact value at the window, in the model.
bool wraps_in_model(const Window5& w, const Formats& f, Reg r) {
    for (bool maximise : {true, false}) {
        const WindowValue x = window_values(w, f, maximise)[idx(r)];
        if (x.exact != x.narrowed) return true;
    }
    return false;
}

/// The solver on one open register: can the exact value differ from the hardware value?
/// (solve_wrap), then (solve_extreme) the exact extreme on the side of the bound that leaves the register, by a binary
/// search of `exists window: exact > T` (or < T), all within `budget` seconds.
SolverVerdict wrap_question(const Formats& f, Reg r, const RangeOptions& o, std::int64_t rlimit, std::int64_t* spent = nullptr) {
    const SolverAnswer w = ask_solver(f, r, o.pixel_max, "(distinct exact hw)", rlimit);
    if (spent) *spent += w.rlimit;
    SolverVerdict v;
    v.why = w.why;
    if (w.sat == Sat::unsat) v.verdict = Verdict::proven;
    if (w.sat == Sat::sat) {
        if (!wraps_in_model(w.window, f, r))
            throw std::logic_error(fmt::format("solver's window for {} does not wrap in the model", kRegNames[idx(r)]));
        v.verdict = Verdict::wraps;
        v.window = w.window;
        v.exact = w.exact;
    }
    return v;
}

/// A budget of z3 resource units, spent query by query.
struct Budget {
    std::int64_t left = 0;
    bool enough() const { return left > 1'000'000; }   // below that no query of these sizes ends
    std::int64_t query(std::int64_t limit) const { return std::min(limit, left); }
};

void solve_wrap(RegisterRange& rr, const Formats& f, const RangeOptions& o, Budget& budget) {
    const auto t0 = Clock::now();
    rr.solver_asked = true;
    std::int64_t spent = 0;
    const SolverVerdict w = wrap_question(f, rr.reg, o, budget.query(o.query_rlimit), &spent);
    budget.left -= spent;
    rr.solver_rlimit += spent;
    rr.verdict = w.verdict;
    if (w.verdict == Verdict::proven) rr.solver = "unsat: cannot wrap";
    if (w.verdict == Verdict::wraps) {
        rr.witness = w.window;
        rr.solver = "sat: a window wraps it";
        rr.solver_reached = w.exact;
    }
    if (w.verdict == Verdict::open) rr.solver = w.why;
    rr.solver_seconds = since(t0);
}

/// The exact extreme of a register's value on one side (hi: its maximum), by a binary search
/// between `known` (a value some window reaches) and `limit` (a value proven not exceeded):
/// returns them as far as the solver got within `budget` (equal: the extreme is exact).
std::pair<std::int64_t, std::int64_t> bracket_extreme(const Formats& f, Reg r, const RangeOptions& o, bool hi, std::int64_t known,
                                                      std::int64_t limit, Budget& budget, std::int64_t* spent = nullptr) {
    while (known != limit && budget.enough()) {
        const std::int64_t mid = known + (limit - known) / 2;   // hi: known <= mid < limit; lo: limit < mid <= known
        const std::string goal = hi ? fmt::format("(bvsgt exact {})", bv64(mid)) : fmt::format("(bvslt exact {})", bv64(mid));
        const SolverAnswer a = ask_solver(f, r, o.pixel_max, goal, budget.query(o.query_rlimit));
        budget.left -= a.rlimit;
        if (spent) *spent += a.rlimit;
        if (a.sat == Sat::sat) known = a.exact;
        else if (a.sat == Sat::unsat) limit = mid;
        else break;
        if (hi ? known > limit : known < limit) throw std::logic_error("solver: a model beyond a proven bound");
    }
    return {known, limit};
}

/// The exact extreme of an open register on the side of its bound that leaves it.
void solve_extreme(RegisterRange& rr, const Formats& f, const RangeOptions& o, Budget& budget) {
    const auto t0 = Clock::now();
    const bool hi = rr.bound.hi > rr.held.hi || rr.bound.lo >= rr.held.lo;
    std::int64_t known = hi ? rr.bound.lo : rr.bound.hi;
    if (rr.searched) known = hi ? std::max(known, rr.reached.hi) : std::min(known, rr.reached.lo);
    if (rr.solver_reached) known = hi ? std::max(known, *rr.solver_reached) : std::min(known, *rr.solver_reached);
    if (!rr.searched && !rr.solver_reached) return;   // no value known to be reached
    const auto [k, l] = bracket_extreme(f, rr.reg, o, hi, known, hi ? rr.bound.hi : rr.bound.lo, budget, &rr.solver_rlimit);
    rr.extreme_side = hi ? 1 : -1;
    rr.extreme = hi ? Interval{k, l} : Interval{l, k};
    rr.solver_seconds += since(t0);
}

/// The exact range of a proven register whose interval bound may be loose (both extremes by
/// the solver, from the values the witness search reaches): solver_range holds what is proven.
void solve_range(RegisterRange& rr, const Formats& f, const RangeOptions& o, std::int64_t limit) {
    const auto t0 = Clock::now();
    // start from what the witness search reaches on each side (a fifth of its windows each)
    RangeOptions quick = o;
    quick.search_windows = std::max<std::int64_t>(1, o.search_windows / 5);
    RegisterRange up = rr, down = rr;
    search_witness(up, f, quick, true);
    search_witness(down, f, quick, false);
    Budget half{limit / 2};
    const auto [khi, lhi] = bracket_extreme(f, rr.reg, o, true, up.reached.hi, rr.bound.hi, half, &rr.solver_rlimit);
    Budget rest{limit - rr.solver_rlimit};
    const auto [klo, llo] = bracket_extreme(f, rr.reg, o, false, down.reached.lo, rr.bound.lo, rest, &rr.solver_rlimit);
    rr.solver_asked = true;
    rr.solver_seconds = since(t0);
    if (Interval{llo, lhi} == rr.bound) {
        rr.solver = klo == llo && khi == lhi ? "the interval bound is exact (a window reaches both ends)" : "no tighter range proven";
        return;
    }
    rr.solver_range = Interval{llo, lhi};
    rr.solver_range_reached = klo == llo && khi == lhi;
    rr.solver = fmt::format("exact value in [{}, {}]{}", llo, lhi, rr.solver_range_reached ? " (both ends reached)" : "");
}

}  // namespace

SolverVerdict solver_wrap(const Formats& f, Reg r, const RangeOptions& o) { return wrap_question(f, r, o, o.query_rlimit); }

SolverExtreme solver_extreme(const Formats& f, Reg r, bool maximise, const RangeOptions& o, std::int64_t rlimit) {
    const Interval b = interval_ranges(f, o.pixel_max).at(r).bound;
    Budget budget{rlimit};
    const auto [k, l] = bracket_extreme(f, r, o, maximise, 0, maximise ? b.hi : b.lo, budget);   // the flat window: 0
    return {k, l};
}

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
    rep.seconds_search = since(t0);
    // det and the response through the block sums' relations, where their bounds do not fit and no witness was found
    if (const ResponseRelation rel = response_relation(rep); rel.applies)
        for (auto [r, range, ok] : {std::tuple{Reg::det, rel.det, rel.det_fits}, std::tuple{Reg::response, rel.response, rel.response_fits}}) {
            RegisterRange& rr = rep.regs[idx(r)];
            if (rr.verdict != Verdict::open) continue;
            rr.relation = (ok ? "proven: " : "does not fit: ") + rel.why;
            rr.relation_range = range;
            if (ok) rr.verdict = Verdict::proven;
        }
    // the solver where the search found no witness (the maximum is the response's: below),
    // first whether each open register can wrap, then its exact extreme, within the budget
    const auto t1 = Clock::now();
    Budget budget{o.solver_rlimit};
    // the maximum is not asked: it takes the response's verdict (below)
    const bool open = std::any_of(rep.regs.begin(), rep.regs.end(),
                                  [](const RegisterRange& x) { return x.verdict == Verdict::open && x.reg != Reg::maximum; });
    if (o.solver_rlimit > 0 && open) {
        rep.query_rlimit = o.query_rlimit;
        // the products' intervals are loose (b = ix*iy: x and y share pixels): their exact
        // ranges (3x3 queries, fast) as the block sums' inputs, proven, tighten what follows
        Tightened tight{};
        for (Reg mr : {Reg::m_a, Reg::m_b, Reg::m_c}) {
            RegisterRange& x = rep.regs[idx(mr)];
            if (x.verdict != Verdict::proven || !budget.enough()) continue;
            solve_range(x, f, o, std::min(budget.left, o.solver_rlimit / 6));
            budget.left -= x.solver_rlimit;
            if (x.solver_range) tight[idx(mr)] = x.solver_range;
        }
        const RangeReport under = interval_ranges(f, o.pixel_max, &tight);
        for (auto& rr : rep.regs) {
            const RegisterRange& u = under.at(rr.reg);
            if (rr.verdict != Verdict::open || rr.reg == Reg::maximum || !u.bound_fits) continue;
            rr.verdict = Verdict::proven;
            rr.solver_asked = true;
            rr.solver = fmt::format("proven: interval bound [{}, {}] under the M registers' exact ranges", u.bound.lo, u.bound.hi);
        }
        for (auto& rr : rep.regs)
            if (rr.verdict == Verdict::open && rr.reg != Reg::maximum && budget.enough()) solve_wrap(rr, f, o, budget);
        for (auto& rr : rep.regs)
            if (rr.solver_asked && !rr.solver_range && rr.verdict != Verdict::proven && budget.enough()) solve_extreme(rr, f, o, budget);
    }
    rep.seconds_solver = since(t1);
    rep.solver_rlimit = o.solver_rlimit - budget.left;
    for (auto& rr : rep.regs)
        rr.decided_by = rr.bound_fits                     ? "interval"
                        : rr.verdict == Verdict::open     ? ""
                        : rr.solver_asked                 ? "model-smt"
                        : rr.verdict == Verdict::proven   ? "relation"
                                                          : "search";
    // the maximum holds a response: it wraps with the response's witness, is proven with it
    RegisterRange& m = rep.regs[idx(Reg::maximum)];
    const RegisterRange& r = rep.regs[idx(Reg::response)];
    if (!m.bound_fits && r.verdict != Verdict::open) {
        m.verdict = r.verdict;
        m.witness = r.witness;
        m.decided_by = r.decided_by;
    }
    if (!m.bound_fits && r.solver_asked) {
        m.solver_asked = true;
        m.solver = r.solver + " (the response's)";
        m.extreme_side = r.extreme_side;
        m.extreme = r.extreme;
    }
    if (o.netlist) netlist_route(rep, o);
    return rep;
}

json range_report_to_json(const RangeReport& r) {
    json regs = json::array();
    for (const auto& x : r.regs) {
        json e = {{"register", kRegNames[idx(x.reg)]}, {"bound", interval_json(x.bound)}, {"held", interval_json(x.held)},
                  {"width", x.width}, {"bound_fits", x.bound_fits}, {"verdict", verdict_name(x.verdict)},
                  {"searched", x.searched}};
        if (!x.relation.empty()) {
            e["relation"] = x.relation;
            e["relation_range"] = interval_json(*x.relation_range);
        }
        if (x.searched) {
            e["reached"] = interval_json(x.reached);
            e["search_windows"] = x.search_windows;
        }
        if (x.verdict == Verdict::wraps) e["witness"] = x.witness;
        e["solver_asked"] = x.solver_asked;
        if (x.solver_asked) {
            e["solver"] = x.solver;
            e["solver_seconds"] = x.solver_seconds;
            if (x.solver_reached) e["solver_reached"] = *x.solver_reached;
            e["extreme_side"] = x.extreme_side;
            if (x.extreme_side) e["extreme"] = interval_json(x.extreme);
            if (x.solver_range) e["solver_range"] = interval_json(*x.solver_range);
            e["solver_range_reached"] = x.solver_range_reached;
            e["solver_rlimit"] = x.solver_rlimit;
        }
        e["netlist_asked"] = x.netlist_asked;
        if (x.netlist_asked) {
            e["netlist_verdict"] = verdict_name(x.netlist_verdict);
            e["netlist"] = x.netlist;
            e["netlist_rlimit"] = x.netlist_rlimit;
            if (x.netlist_range) e["netlist_range"] = interval_json(*x.netlist_range);
            e["netlist_vhdl"] = x.netlist_vhdl;
            e["netlist_differs"] = x.netlist_differs;
            if (x.netlist_differs) {
                e["netlist_value"] = x.netlist_value;
                e["vhdl_value"] = x.vhdl_value;
            }
        }
        e["decided_by"] = x.decided_by;
        regs.push_back(e);
    }
    return {{"flow", kRangesVersion}, {"formats", fields_text(r.formats, format_fields())}, {"pixel_max", r.pixel_max},
            {"key", r.key}, {"verdict", verdict_name(r.overall())}, {"summary", r.summary()},
            {"seconds_interval", r.seconds_interval}, {"seconds_search", r.seconds_search}, {"seconds_solver", r.seconds_solver},
            {"seconds_netlist", r.seconds_netlist}, {"query_rlimit", r.query_rlimit}, {"netlist_query_rlimit", r.netlist_query_rlimit},
            {"solver_rlimit", r.solver_rlimit}, {"netlist_rlimit", r.netlist_rlimit}, {"netlist_note", r.netlist_note},
            {"registers", regs}};
}

RangeReport range_report_from_json(const json& j) {
    RangeReport r;
    if (j.at("flow").get<std::string>() != kRangesVersion) throw std::invalid_argument("range report of another analysis version");
    r.pixel_max = j.at("pixel_max");
    r.key = j.at("key");
    r.seconds_interval = j.at("seconds_interval");
    r.seconds_search = j.at("seconds_search");
    r.seconds_solver = j.at("seconds_solver");
    r.seconds_netlist = j.at("seconds_netlist");
    r.query_rlimit = j.at("query_rlimit");
    r.netlist_query_rlimit = j.at("netlist_query_rlimit");
    r.solver_rlimit = j.at("solver_rlimit");
    r.netlist_rlimit = j.at("netlist_rlimit");
    r.netlist_note = j.at("netlist_note");
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
        x.verdict = verdict_from(e.at("verdict"));
        x.searched = e.at("searched");
        if (e.contains("relation")) {
            x.relation = e.at("relation");
            x.relation_range = interval_from(e.at("relation_range"));
        }
        if (x.searched) {
            x.reached = interval_from(e.at("reached"));
            x.search_windows = e.at("search_windows");
        }
        if (x.verdict == Verdict::wraps) x.witness = e.at("witness").get<Window5>();
        x.solver_asked = e.at("solver_asked");
        if (x.solver_asked) {
            x.solver = e.at("solver");
            x.solver_seconds = e.at("solver_seconds");
            if (e.contains("solver_reached")) x.solver_reached = e.at("solver_reached").get<std::int64_t>();
            x.extreme_side = e.at("extreme_side");
            if (x.extreme_side) x.extreme = interval_from(e.at("extreme"));
            if (e.contains("solver_range")) x.solver_range = interval_from(e.at("solver_range"));
            x.solver_range_reached = e.at("solver_range_reached");
            x.solver_rlimit = e.at("solver_rlimit");
        }
        x.netlist_asked = e.at("netlist_asked");
        if (x.netlist_asked) {
            x.netlist_verdict = verdict_from(e.at("netlist_verdict"));
            x.netlist = e.at("netlist");
            x.netlist_rlimit = e.at("netlist_rlimit");
            if (e.contains("netlist_range")) x.netlist_range = interval_from(e.at("netlist_range"));
            x.netlist_vhdl = e.at("netlist_vhdl");
            x.netlist_differs = e.at("netlist_differs");
            if (x.netlist_differs) {
                x.netlist_value = e.at("netlist_value");
                x.vhdl_value = e.at("vhdl_value");
            }
        }
        x.decided_by = e.at("decided_by");
        r.regs.push_back(x);
    }
    return r;
}

namespace {

/// The options a cached report must have been made with to be read back: every one that can
/// change a verdict or a bracket (the pixel range, the search, the budgets, the netlist route).
std::string cache_options(const RangeOptions& o) {
    return fmt::format("pixel_max={} search_windows={} seeds={} solver_rlimit={} query_rlimit={} netlist={} "
                       "netlist_budget={} netlist_query_rlimit={}",
                       o.pixel_max, o.search_windows, o.seeds, o.solver_rlimit, o.query_rlimit, o.netlist,
                       o.netlist_budget, o.netlist_query_rlimit);
}

}  // namespace

RangeReport cached_ranges(const Formats& f, const std::string& key, const fs::path& cache_dir, const RangeOptions& o) {
    const fs::path p = cache_dir / (key + ".json");
    const std::string options = cache_options(o);
    if (fs::exists(p)) {
        try {
            const json j = json::parse(util::read_file(p));
            if (j.value("options", std::string()) == options) {
                RangeReport r = range_report_from_json(j);
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
    json j = range_report_to_json(r);
    j["options"] = options;
    util::write_file_atomic(p, j.dump(1) + "\n");
    return r;
}

}  // namespace hc::sweep
