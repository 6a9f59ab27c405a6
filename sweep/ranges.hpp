// ranges.hpp: derived ranges of every datapath register of a configuration, for every
// input: proven safe, wraps (with a pixel window that wraps it), or open.
//
// Purpose: the overflow audit (overflow.hpp) proves a wrap on data, never its absence. Here
//   1. the interval bound: the shared stage functions (model/harris/*.hpp) run on
//      RangeWord (model/fixed/range_word.hpp) from pixels anywhere in [0, pixel_max],
//      giving a sound bound on the exact value of each register (on its narrowed inputs,
//      as the audit defines it) and every narrowing in its stage where that bound does not
//      fit. A register whose bound fits everywhere is proven: it cannot wrap for any input.
//   2. where it does not fit, a search for a 5x5 pixel window that wraps it: structured
//      seeds (the Sobel kernels' sign patterns, column and row stripes, diagonals, random
//      vertices) improved by coordinate ascent on the register's exact value, evaluated by
//      the same stage functions on Word. A window whose value leaves the register's range
//      is a witness (checked again by the overflow audit on the window's image).
//   3. where the search found none, the exact question to z3 as an SMT-LIB bit-vector query:
//      the 25 pixels of a window are variables, the stage functions run on a number type
//      that writes their numeric_std arithmetic as bit-vector terms, and the query asks for
//      a window where the register's exact value differs from its hardware value: unsat is
//      proven (cannot wrap), sat is a witness (checked in the model), z3 giving up at its resource limit leaves it
//      open. Then a binary search of "exists window: exact > T" queries brackets the exact
//      extreme on the side that leaves the register, within the configuration's budget.
//   4. the netlist route (ranges_netlist.cpp): GHDL synthesises the stage entities at the
//      configuration's generics, yosys turns the stage chain (a 5x5 window through Sobel,
//      M, the block sums and the response) into SMT-LIB, and z3 asks each register's
//      question on that netlist: stage by stage, the stage's inputs assumed in the ranges
//      proven on the netlist for the stage before (assume-guarantee), and from the 25
//      pixels through the whole chain where the stage's question is satisfiable. unsat is
//      proven on the netlist, sat a window (checked in the model), unknown open. A register
//      on which the two routes disagree (one proves it, the other has a window) is an error,
//      except where a signed resize to fewer bits may overflow upstream: GHDL's synthesis
//      truncates it (numeric_std keeps the sign bit), so there the netlist is not the VHDL
//      and the report says so (signed_shrinks, RegisterRange::netlist_vhdl, netlist_differs).
//   5. otherwise the register is open: the bound, the best value the search reached and
//      where the solvers stopped.
// Every z3 query is limited by z3's resource limit (rlimit), not by time, so verdicts and
// brackets do not depend on the machine's speed.
// The exact value of a register at the window (the audit's "exact"): Sobel and the
// products are exact integers; block sum floor(sum of the nine M / 2^bf_drop); trace a+c;
// det a*c and b*b (each resized to resp_w in the response); k-term floor(tr^2/2^k_shift1)
// + floor(tr^2/2^k_shift2); response a*c - b*b - ktr2; maximum: a response (or the reset
// value); threshold floor(max/2^thr_shift1) + floor(max/2^thr_shift2).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "model/fixed/range_word.hpp"
#include "model/harris/harris_pkg.hpp"
#include "model/image/image.hpp"
#include "sweep/overflow.hpp"

namespace hc::sweep {

enum class Reg { sobel_x, sobel_y, m_a, m_b, m_c, block_a, block_b, block_c, trace, det, k_term, response, maximum, threshold, count };
inline constexpr int kRegCount = static_cast<int>(Reg::count);
inline constexpr std::array<const char*, kRegCount> kRegNames{
    "sobel_x", "sobel_y", "m_a", "m_b", "m_c", "block_a", "block_b", "block_c",
    "trace", "det", "k_term", "response", "maximum", "threshold"};
/// The overflow audit's stage that counts a wrap of the register (stage_count: none;
/// the trace and the threshold are not audited).
Stage audit_stage(Reg r);

enum class Verdict { proven, wraps, open };
const char* verdict_name(Verdict v);   ///< "proven", "wraps", "open"

/// A 5x5 pixel window, [row][col]: Sobel at its 3x3 interior, one block sum and one response at its centre.
using Window5 = std::array<std::array<int, 5>, 5>;

struct RegisterRange {
    Reg reg = Reg::sobel_x;
    Interval bound;            ///< sound bound on the register's exact value, any input
    Interval held;             ///< what the register holds (its width and signedness)
    int width = 0;
    bool bound_fits = false;   ///< the bound fits every narrowing of the stage
    Verdict verdict = Verdict::open;
    bool searched = false;     ///< the witness search ran (only where the bound does not fit)
    Interval reached;          ///< the exact values the search reached (searched only)
    std::int64_t search_windows = 0;   ///< the windows the search scored (both sides)
    Window5 witness{};         ///< verdict wraps: a window that wraps the register
    // the solver (only where the search found no witness)
    bool solver_asked = false;
    std::string solver;        ///< its answer: "unsat: cannot wrap", "sat: a window wraps it", "unknown: rlimit N reached", ...
    double solver_seconds = 0;
    std::optional<std::int64_t> solver_reached;   ///< sat: the exact value at the solver's window
    int extreme_side = 0;      ///< +1: the maximum of the exact value was bracketed, -1: the minimum, 0: neither
    Interval extreme;          ///< the exact extreme lies in here (lo == hi: exact); the rest of the bound is unreachable
    /// A proven register whose interval bound is loose (the M registers, when something
    /// downstream is not proven): the solver's proof that the exact value lies in here,
    /// used as the next stage's input range; reached: a window attains both ends.
    std::optional<Interval> solver_range;
    bool solver_range_reached = false;
    /// det and the response: their range by response_relation (decided by "relation" where it fits), or ""
    std::string relation;
    std::optional<Interval> relation_range;
    std::int64_t solver_rlimit = 0;   ///< z3's resource units the model route spent on the register
    // the netlist route
    bool netlist_asked = false;
    Verdict netlist_verdict = Verdict::open;
    std::string netlist;              ///< its answer: "unsat on the stage netlist (assuming ...)", "sat from pixels: ...", ...
    std::int64_t netlist_rlimit = 0;  ///< z3's resource units it spent on the register
    std::optional<Interval> netlist_range;   ///< proven on the netlist: the register's hardware value lies in here
    /// Whether the netlist route's answer holds for the VHDL (numeric_std), not only for GHDL's
    /// netlist: "holds for the VHDL: ..." when no signed shrink of the register's stage or
    /// upstream can overflow, else "GHDL's netlist only: resize(...) may overflow".
    std::string netlist_vhdl;
    /// The netlist computes another value than the VHDL at the model's witness (a signed
    /// shrink overflows there): the netlist's value at the witness, the model's (numeric_std) beside it.
    bool netlist_differs = false;
    std::int64_t netlist_value = 0, vhdl_value = 0;
    /// which route decided the verdict: "interval", "search", "relation" (response_relation),
    /// "model-smt" (z3 on the model's arithmetic), "netlist" (z3 on GHDL's netlist), "" (open)
    std::string decided_by;
};

struct RangeReport {
    Formats formats;
    int pixel_max = 255;
    std::vector<RegisterRange> regs;   ///< one per Reg, in Reg order
    double seconds_interval = 0, seconds_search = 0, seconds_solver = 0, seconds_netlist = 0;
    std::int64_t query_rlimit = 0, netlist_query_rlimit = 0;   ///< the per-query resource limits used (0: route not run)
    std::int64_t solver_rlimit = 0, netlist_rlimit = 0;        ///< resource units each route spent in all
    std::string netlist_note;          ///< why the netlist route did not run, or how its netlists were made
    bool cached = false;
    std::string key;                   ///< cache key (the sweep's synthesis key), or ""
    /// proven when every register is; wraps when one wraps; else open
    Verdict overall() const;
    /// The first register that wraps, or nullptr.
    const RegisterRange* first_wrap() const;
    /// "proven safe", "wraps at block_a", "open (response: bound [lo, hi], reached [lo, hi])"
    std::string summary() const;
    /// Which route decided how many registers, and what the netlist route said:
    /// "interval 12, search 2; netlist: 11 proven, 2 wraps, 0 open of 13" ("netlist not run" without it).
    std::string routes() const;
    const RegisterRange& at(Reg r) const { return regs[static_cast<int>(r)]; }
};

struct RangeOptions {
    int pixel_max = 255;          ///< pixels anywhere in [0, pixel_max] (8-bit: 255)
    /// windows the witness search scores per register and side, at most (a count, so that
    /// two runs score the same windows and give the same verdicts on any machine). No
    /// configuration of sweep/configs/bit-widths.json, nor resp_w=29, needs more than 90,000.
    std::int64_t search_windows = 1'000'000;
    int seeds = 64;               ///< random 0/255 windows per register and side
    /// The model route's budget for the configuration, in z3 resource units (0: no solver);
    /// on this project's machine z3 spends about 5 million units per second of CPU.
    std::int64_t solver_rlimit = 110'000'000;
    std::int64_t query_rlimit = 40'000'000;            ///< one query of the model route, at most
    bool netlist = true;                               ///< run the netlist route (GHDL, yosys and z3)
    std::int64_t netlist_budget = 90'000'000;          ///< the netlist route's budget (resource units)
    std::int64_t netlist_query_rlimit = 40'000'000;    ///< one query of the netlist route, at most
    /// keep the netlists, their scripts and every query of the netlist route here (query-<register>-<k>.smt2,
    /// k counting that register's queries from 1); empty: a scratch directory
    std::filesystem::path netlist_dir;
};

/// Proven ranges of registers' exact values that replace their interval bounds as the next
/// stage's input (only for registers the interval part proves).
using Tightened = std::array<std::optional<Interval>, kRegCount>;
/// Only the interval part: bounds and fits, every verdict proven or open (no search).
RangeReport interval_ranges(const Formats& f, int pixel_max = 255, const Tightened* tight = nullptr);
/// The whole analysis: interval bounds, then the witness search where they do not fit, then
/// the solver (z3 on PATH; without it the register stays open, saying so) where the search found none.
RangeReport analyse_ranges(const Formats& f, const RangeOptions& o = {});

/// det and the response bounded through the relations one window's gradients impose on the
/// block sums, where Sobel, M, the block sums and the k-term are proven by their interval
/// bounds (their hardware values are their exact values) and a, c >= 0:
///   energy = max of ix^2 + iy^2 over the pixel box, at one of its 512 vertices (ix, iy are
///     linear in the pixels, the sum of their squares convex);
///   per position ma + mc <= floor(energy / 2^m_drop), so a + c <= T = floor(9 floor(energy /
///     2^m_drop) / 2^bf_drop) (a floor of a sum is at least the sum of the floors);
///   a*c <= floor(T/2) ceil(T/2);
///   Cauchy-Schwarz over the nine positions, with every floor's slack: |b| < sqrt((a + g)(c + g))
///     + g, g = 1 + ceil(9 / 2^bf_drop); so b*b < (T/2 + 2g)^2 and a*c - b*b > -2gT - 4g^2;
///   ktr2 <= floor(T^2 / 2^k_shift1) + floor(T^2 / 2^k_shift2).
/// det cannot wrap when a*c and b*b fit resp_w signed bits; the response when ktr2 and its own
/// range fit too (the response's sum is modular, the resizes exact).
struct ResponseRelation {
    bool applies = false;            ///< the preconditions hold (else `why` says which fails)
    std::int64_t energy = 0, trace = 0, g = 0;
    Interval ac, bb, det, ktr2, response;   ///< sound ranges of the exact values
    bool det_fits = false, response_fits = false;
    std::string why;                 ///< the ranges and what they rest on, or why the relation does not apply
};
ResponseRelation response_relation(const RangeReport& rep);

/// The solver's answer to "is there a window of pixels in [0, pixel_max] where register r's
/// exact value differs from its hardware value?" (z3 on PATH, one query of at most
/// o.query_rlimit resource units): proven (unsat), wraps (sat; the window wraps r in the model, else
/// std::logic_error), open (why: "unknown: rlimit N reached", "no solver: ...").
struct SolverVerdict {
    Verdict verdict = Verdict::open;
    Window5 window{};
    std::int64_t exact = 0;   ///< wraps: r's exact value at the window
    std::string why;
};
SolverVerdict solver_wrap(const Formats& f, Reg r, const RangeOptions& o = {});
/// The solver's bracket of r's exact maximum (maximise) or minimum within `rlimit` resource units:
/// `reached` is attained by a window, no window goes beyond `proven` (equal: exact).
struct SolverExtreme {
    std::int64_t reached = 0, proven = 0;
};
SolverExtreme solver_extreme(const Formats& f, Reg r, bool maximise, const RangeOptions& o, std::int64_t rlimit);

/// One z3 run on an SMT-LIB text (`z3 -smt2 rlimit=N`): its first answer, the values of the
/// 0-ary functions `get` as the model gives them (sat only), the resource units it spent.
/// `keep` (when not empty): the whole query, as z3 reads it, is also written there.
enum class Sat { sat, unsat, unknown };
struct Z3Answer {
    Sat sat = Sat::unknown;
    std::map<std::string, std::int64_t> values;
    std::int64_t rlimit = 0;
    std::string why;   ///< unknown: "rlimit N reached", "no solver: ...", z3's message
};
Z3Answer run_z3(const std::string& smt, std::int64_t rlimit, const std::vector<std::string>& get,
                const std::filesystem::path& keep = {});

/// GHDL's netlists of the stage chain at formats `f`, as SMT-LIB by yosys (write_smt2 of a
/// combinational module: each register replaced by its input, as in a pipeline whose inputs
/// hold still; refused when a register has an enable or reset that does not fold away).
/// chain: 25 pixel inputs p_<row>_<col> through nine sobel_x, sobel_y and m_products, three
/// block_filter and one harris_response; block: the three block_filter with the 27 M values
/// as inputs; response: harris_response with a, b, c as inputs. Wires keep the chain's names
/// (ix_<i>_<j>, ma_<i>_<j>, a, b, c, hr.ac, hr.bb, hr.trace, hr.ktr2, r) in all three.
struct StageNetlists {
    std::string chain, block, response;   ///< SMT-LIB texts (modules chain, stage_block, stage_response)
    std::string commands;                 ///< the GHDL and yosys commands that made them
};
/// The generics of stage entity `e` at formats `f` as GHDL flags ("-gSOBEL_W=11", ...): each entity takes only its own
/// (find_max also the image size `g` its period is built for).
std::vector<std::string> entity_generics(const std::string& e, const Formats& f, const Geometry& g = {});
/// Synthesises in `dir` (kept; commands.txt: the commands). SimulatorError when GHDL or yosys is missing or fails.
StageNetlists stage_netlists(const Formats& f, const std::filesystem::path& dir);
/// The netlist's value (hardware, as RegisterRange's questions read it) of every register it
/// holds at window `w`: Sobel and M at the window's top-left 3x3 position, the rest at its
/// centre; the threshold (computed in harris_top, outside the chain) is absent.
std::array<std::optional<std::int64_t>, kRegCount> netlist_values(const StageNetlists& n, const Formats& f, const Window5& w);
/// A resize of a signed value to fewer bits in the stage chain at formats `f`. numeric_std
/// keeps the sign bit and the low to-1 bits; GHDL's --synth (2.0) keeps the low `to` bits
/// (tests/sweep/numeric_std_synth_test.cpp), so the netlist is the VHDL there only where the
/// value fits `to` bits.
struct SignedShrink {
    std::string what;        ///< "resize(ac, RESP_W) in harris_response"
    int from = 0, to = 0;    ///< the operand's width, the resized width
    std::vector<Reg> feeds;  ///< the registers of its stage it feeds
    Interval operand;        ///< a sound bound on the operand's value (the report's ranges)
    bool fits = false;       ///< the bound fits `to` bits: the shrink cannot overflow
};
/// Every signed shrink of the stage chain at the report's formats, with the bound of its operand
/// from the report's ranges (a register the model route proves in its bound or the solver's
/// range, any other in what its width holds).
std::vector<SignedShrink> signed_shrinks(const RangeReport& rep);

/// The netlist route on a report the model route made (analyse_ranges runs it when o.netlist):
/// every register of the chain is asked on the netlist; a register the model route left open
/// takes the netlist's verdict where that holds for the VHDL (no signed shrink upstream may
/// overflow: RegisterRange::netlist_vhdl). Where a signed shrink may overflow, a model witness
/// the netlist does not wrap is reported as the netlist differing from the VHDL there
/// (netlist_differs), not as a fault. std::logic_error when the routes disagree (one proves,
/// the other has a window) or a netlist window does not wrap in the model, where no signed
/// shrink may overflow.
void netlist_route(RangeReport& rep, const RangeOptions& o);

/// The exact value and the hardware value of every register at the window's centre
/// (Sobel and M: the extreme over the 3x3 positions), by the stage functions on Word.
struct WindowValue {
    std::int64_t exact = 0, narrowed = 0;
};
std::array<WindowValue, kRegCount> window_values(const Window5& w, const Formats& f, bool maximise);
/// The witness window as an image the co-processor can take: the window at the centre of
/// a width x height frame (at least 10x8), the rest replicating the window's nearest edge pixel.
Image witness_image(const Window5& w, int width = 16, int height = 12);

/// "sobel_w-10_sobel_x": a file stem for the witness of register `r` of configuration `config`
/// (characters other than letters, digits, '-' and '_' become '-').
std::string witness_stem(const std::string& config, Reg r);
/// `name` with characters other than letters, digits, '-' and '_' replaced by '-'.
std::string file_stem(const std::string& name);

/// The report as Markdown: one row per register (bound, what it holds, verdict, search, witness).
std::string ranges_markdown(const std::string& config, const RangeReport& r);

/// A witness written as a stimulus: the window's image and the configuration it breaks.
struct WitnessFile {
    Reg reg = Reg::sobel_x;
    std::filesystem::path image;     ///< <dir>/<witness_stem>.pgm, witness_image() of the window
    std::filesystem::path formats;   ///< <dir>/<config>.json, the --config file of the configuration
    /// The regression-set line of the stream (paths relative to `set_dir`): the image chained
    /// twice (the second frame is thresholded with the first's maximum), breaks=the formats.
    std::string regression_line(const std::filesystem::path& set_dir) const;
};
/// Writes every witness of `r` (one per register that wraps) under `dir`.
std::vector<WitnessFile> write_witnesses(const std::string& config, const RangeReport& r, const std::filesystem::path& dir);

nlohmann::json range_report_to_json(const RangeReport& r);
RangeReport range_report_from_json(const nlohmann::json& j);   ///< throws on a malformed document

/// analyse_ranges cached as <cache_dir>/<key>.json (key: the configuration's synthesis
/// key, sweep/cost.hpp); an entry of another analysis version, or made with other options
/// (pixel range, search, budgets, netlist route), is recomputed and replaced.
RangeReport cached_ranges(const Formats& f, const std::string& key, const std::filesystem::path& cache_dir,
                          const RangeOptions& o = {});

}  // namespace hc::sweep

namespace hc::sweep {

/// One width field of Formats in a proposal (propose_widths).
struct ProposedWidth {
    std::string field;              ///< the field's name in format_fields() ("resp_w")
    int base = 0, proposed = 0;
    std::vector<Reg> regs;          ///< the registers whose width the field sets
    Reg setter = Reg::sobel_x;      ///< the register with the fewest bits to spare: it sets `proposed`
    Interval range;                 ///< the setter's proven range
    int bits = 0;                   ///< the fewest bits (of the setter's signedness) that hold `range`
    std::string from;               ///< what `range` rests on ("interval bound", "exact maximum (solver)", ...)
    std::string kept;               ///< why the width stays at `base` when it could not be narrowed ("" otherwise)
};
/// The narrowest widths a range report proves safe, and how each was set.
struct WidthProposal {
    Formats base, formats;          ///< the report's formats; the proposal (only width fields differ)
    std::vector<ProposedWidth> widths;   ///< one per width field, in format_fields() order
};

/// The narrowest widths that hold every register's proven range, from a configuration's report.
/// A width field is a field of format_fields() that, raised by one, widens registers of the
/// report's table by one bit and narrows none (the drops and the shifts are not widths); the
/// registers it widens are the ones it governs. Each register's proven range is its interval
/// bound, with the solver's closed exact extreme on its side where the solver closed it (not
/// for det, whose narrowings are a*c and b*b, not det); the maximum's is the response's (its
/// other value, the reset, is the most negative of any width). For det, the response and the
/// maximum, where the block sums' relations apply (response_relation) and need fewer bits: the
/// hull of the values their stage narrows (a*c, b*b, det; and the k-term and the response). A
/// width is its base value minus the fewest bits any governed register has to spare; it stays
/// where a governed register is not proven (wraps, open), and where a register the base proves
/// by its interval bound or the relations is proven by neither at the proposal's widths (a
/// narrowing inside a stage). Drops and shifts are unchanged.
WidthProposal propose_widths(const RangeReport& rep);
/// The report's section: one row per width field (base, proposed, the register and range that set it).
std::string proposal_markdown(const WidthProposal& p);

}  // namespace hc::sweep
