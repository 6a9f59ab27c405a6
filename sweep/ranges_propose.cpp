// ranges_propose.cpp: the narrowest widths a range report proves safe (propose_widths in ranges.hpp).
#include <algorithm>
#include <initializer_list>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "sweep/ranges.hpp"

namespace hc::sweep {

namespace {

constexpr int idx(Reg r) { return static_cast<int>(r); }

/// The registers whose width grows by one bit when `field` grows by one, or empty when the
/// field is not a width (it changes no register's width, or narrows one: a drop).
std::vector<Reg> governed(const RangeReport& rep, const FormatField& field) {
    Formats wider = rep.formats;
    ++(wider.*(field.member));
    try {
        wider.validate();
    } catch (const std::invalid_argument&) {
        return {};
    }
    const RangeReport w = interval_ranges(wider, rep.pixel_max);
    std::vector<Reg> regs;
    for (int i = 0; i < kRegCount; ++i) {
        const int d = w.regs[i].width - rep.regs[i].width;
        if (d != 0 && d != 1) return {};
        if (d == 1) regs.push_back(static_cast<Reg>(i));
    }
    return regs;
}

/// The register's proven range and what it rests on (see propose_widths).
Interval proven_range(const RangeReport& rep, Reg r, std::string& from) {
    if (r == Reg::maximum) {
        from = "the response's range (its other value, the reset, is the width's most negative)";
        r = Reg::response;
    } else {
        from = "interval bound";
    }
    const RegisterRange& x = rep.at(r);
    Interval range = x.bound;
    if (r != Reg::det && x.extreme_side != 0 && x.extreme.lo == x.extreme.hi) {
        if (x.extreme_side > 0) range.hi = std::min(range.hi, x.extreme.hi);
        else range.lo = std::max(range.lo, x.extreme.lo);
        from += x.extreme_side > 0 ? ", exact maximum (solver)" : ", exact minimum (solver)";
    }
    return range;
}

int fewest_bits(const Interval& v, bool is_signed) {
    for (int w = 1; w <= 62; ++w)
        if (fits(v, w, is_signed)) return w;
    throw std::logic_error(fmt::format("propose_widths: [{}, {}] fits no width", v.lo, v.hi));
}

Interval hull(std::initializer_list<Interval> parts) {
    Interval h = *parts.begin();
    for (const Interval& x : parts) h = {std::min(h.lo, x.lo), std::max(h.hi, x.hi)};
    return h;
}

/// What the block sums' relations (response_relation) prove of det, the response and the
/// maximum, whatever resp_w is: every value their stage narrows to resp_w lies in the hull
/// returned (det: a*c, b*b and det; the response and the maximum, which takes the response's
/// values: also the k-term and the response). Empty for another register or when the relation
/// does not apply.
std::optional<Interval> relation_range(const ResponseRelation& rel, Reg r) {
    if (!rel.applies) return std::nullopt;
    if (r == Reg::det) return hull({rel.ac, rel.bb, rel.det});
    if (r == Reg::response || r == Reg::maximum) return hull({rel.ac, rel.bb, rel.det, rel.ktr2, rel.response});
    return std::nullopt;
}

/// Whether the relation proves register r at its report's widths (see relation_range).
bool relation_proves(const ResponseRelation& rel, Reg r) {
    if (r == Reg::det) return rel.applies && rel.det_fits;
    if (r == Reg::response || r == Reg::maximum) return rel.applies && rel.response_fits;
    return false;
}

/// One width field from the report: the setter, its range, the proposed value (or why it stays).
ProposedWidth propose_field(const RangeReport& rep, const ResponseRelation& rel, const FormatField& field,
                            const std::vector<Reg>& regs) {
    ProposedWidth p;
    p.field = field.name;
    p.base = p.proposed = rep.formats.*(field.member);
    p.regs = regs;
    int spare = 0;
    bool first = true;
    for (Reg r : regs) {
        const RegisterRange& x = rep.at(r);
        if (x.verdict != Verdict::proven) {
            p.kept += fmt::format("{}{} {}", p.kept.empty() ? "" : ", ", kRegNames[idx(r)], verdict_name(x.verdict));
            continue;
        }
        std::string from;
        Interval range = proven_range(rep, r, from);
        int bits = fewest_bits(range, x.held.lo < 0);
        if (const auto by_relation = relation_range(rel, r)) {
            const int b = fewest_bits(*by_relation, true);
            if (b < bits) {
                range = *by_relation;
                bits = b;
                from = "the block sums' relations (a*c, b*b, det" + std::string(r == Reg::det ? ")" : ", k-term, response)");
            }
        }
        if (first || x.width - bits < spare) {
            spare = x.width - bits;
            p.setter = r;
            p.range = range;
            p.bits = bits;
            p.from = from;
            first = false;
        }
    }
    if (!p.kept.empty()) p.kept = "not proven: " + p.kept;
    else p.proposed = p.base - spare;
    return p;
}

/// The registers the base's interval pass or the block sums' relations prove that neither proves
/// at the proposal's widths, by name ("" when none).
std::string lost_interval_proofs(const RangeReport& base, const RangeReport& prop, const std::vector<Reg>& regs) {
    const ResponseRelation rel = response_relation(prop);
    std::string lost;
    for (Reg r : regs) {
        const std::string& by = base.at(r).decided_by;
        if ((by == "interval" || by == "relation") && !prop.at(r).bound_fits && !relation_proves(rel, r))
            lost += fmt::format("{}{}", lost.empty() ? "" : ", ", kRegNames[idx(r)]);
    }
    return lost;
}

}  // namespace

WidthProposal propose_widths(const RangeReport& rep) {
    if (static_cast<int>(rep.regs.size()) != kRegCount) throw std::invalid_argument("propose_widths: the report has no register table");
    WidthProposal out;
    out.base = out.formats = rep.formats;
    const ResponseRelation rel = response_relation(rep);
    for (const FormatField& field : format_fields()) {
        const std::vector<Reg> regs = governed(rep, field);
        if (regs.empty()) continue;
        out.widths.push_back(propose_field(rep, rel, field, regs));
        out.formats.*(field.member) = out.widths.back().proposed;
    }
    // a narrowing inside a stage the register's range does not show (the M values resized to
    // the block sum's width, ...): a width whose registers lose their proof stays
    for (bool changed = true; changed;) {
        changed = false;
        const RangeReport prop = interval_ranges(out.formats, rep.pixel_max);
        for (ProposedWidth& w : out.widths) {
            const std::string lost = lost_interval_proofs(rep, prop, w.regs);
            if (lost.empty() || w.proposed == w.base) continue;
            w.kept = fmt::format("{} bits no longer prove {} by the interval bound or the block sums' relations", w.proposed, lost);
            w.proposed = w.base;
            for (const FormatField& field : format_fields())
                if (w.field == field.name) out.formats.*(field.member) = w.base;
            changed = true;
        }
    }
    out.formats.validate();
    return out;
}

std::string proposal_markdown(const WidthProposal& p) {
    std::string md = "### Proposed widths\n\n";
    md += "| width | base | proposed | registers | set by | its proven range | register bits | from |\n";
    md += "|---|---|---|---|---|---|---|---|\n";
    for (const auto& w : p.widths) {
        std::string regs;
        for (Reg r : w.regs) regs += fmt::format("{}{}", regs.empty() ? "" : ", ", kRegNames[idx(r)]);
        if (!w.kept.empty()) {
            md += fmt::format("| `{}` | {} | {} (kept) | {} | | | | {} |\n", w.field, w.base, w.proposed, regs, w.kept);
            continue;
        }
        md += fmt::format("| `{}` | {} | {} | {} | `{}` | [{}, {}] | {} | {} |\n", w.field, w.base, w.proposed, regs,
                          kRegNames[idx(w.setter)], w.range.lo, w.range.hi, w.bits, w.from);
    }
    std::string diff;
    for (const auto& w : p.widths)
        if (w.proposed != w.base) diff += fmt::format("{}{} {} -> {}", diff.empty() ? "" : ", ", w.field, w.base, w.proposed);
    md += fmt::format("\nProposal: {} (drops and shifts unchanged).\n", diff.empty() ? "every width as it is" : diff);
    return md;
}

}  // namespace hc::sweep
