// vhdl_mutants.cpp: the tokenizer and the mutation rules of vhdl_mutants.hpp.
#include "mutation/vhdl_mutants.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

namespace hc::mutation {

namespace {

enum class Tk { ident, number, op, chr, str };

struct Token {
    Tk kind;
    std::string text;    ///< as written
    std::string lower;   ///< lower case (identifiers and keywords)
    std::size_t offset, length;
    int line, column;
};

bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

std::string to_lower(std::string s) {
    for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::vector<Token> tokenize(const std::string& t) {
    std::vector<Token> v;
    std::size_t i = 0;
    int line = 1;
    std::size_t line_start = 0;
    auto push = [&](Tk k, std::size_t a, std::size_t b) {
        Token tok{k, t.substr(a, b - a), to_lower(t.substr(a, b - a)), a, b - a, line,
                  static_cast<int>(a - line_start) + 1};
        v.push_back(std::move(tok));
    };
    while (i < t.size()) {
        const char c = t[i];
        if (c == '\n') {
            ++line;
            line_start = ++i;
            continue;
        }
        if (std::isspace(static_cast<unsigned char>(c))) {
            ++i;
            continue;
        }
        if (c == '-' && i + 1 < t.size() && t[i + 1] == '-') {   // comment to end of line
            while (i < t.size() && t[i] != '\n') ++i;
            continue;
        }
        if (std::isalpha(static_cast<unsigned char>(c))) {
            std::size_t j = i;
            while (j < t.size() && is_ident_char(t[j])) ++j;
            push(Tk::ident, i, j);
            i = j;
            continue;
        }
        if (std::isdigit(static_cast<unsigned char>(c))) {
            std::size_t j = i;
            // digits, underscores, and based (16#FF#) or real (1.5, 1e3) literals as one token
            while (j < t.size() && (is_ident_char(t[j]) || t[j] == '#' || t[j] == '.')) ++j;
            push(Tk::number, i, j);
            i = j;
            continue;
        }
        if (c == '"') {
            std::size_t j = i + 1;
            while (j < t.size() && t[j] != '"' && t[j] != '\n') ++j;
            push(Tk::str, i, std::min(j + 1, t.size()));
            i = j + 1;
            continue;
        }
        if (c == '\'') {
            // an attribute tick after a name or a closing parenthesis, else a character literal
            const bool tick = !v.empty() && ((v.back().kind == Tk::ident && v.back().offset + v.back().length == i) ||
                                             v.back().text == ")");
            if (!tick && i + 2 < t.size() && t[i + 2] == '\'') {
                push(Tk::chr, i, i + 3);
                i += 3;
                continue;
            }
            push(Tk::op, i, i + 1);
            ++i;
            continue;
        }
        static const char* two[] = {"<=", ">=", "/=", "=>", ":=", "**", "<>", "??"};
        bool matched = false;
        for (const char* op : two)
            if (t.compare(i, 2, op) == 0) {
                push(Tk::op, i, i + 2);
                i += 2;
                matched = true;
                break;
            }
        if (matched) continue;
        push(Tk::op, i, i + 1);
        ++i;
    }
    return v;
}

const std::set<std::string>& reserved() {
    static const std::set<std::string> r = {
        "abs", "access", "after", "alias", "all", "and", "architecture", "array", "assert", "attribute",
        "begin", "block", "body", "buffer", "bus", "case", "component", "configuration", "constant",
        "disconnect", "downto", "else", "elsif", "end", "entity", "exit", "file", "for", "function",
        "generate", "generic", "group", "guarded", "if", "impure", "in", "inertial", "inout", "is",
        "label", "library", "linkage", "literal", "loop", "map", "mod", "nand", "new", "next", "nor",
        "not", "null", "of", "on", "open", "or", "others", "out", "package", "port", "postponed",
        "procedure", "process", "pure", "range", "record", "register", "reject", "rem", "report",
        "return", "rol", "ror", "select", "severity", "signal", "shared", "sla", "sll", "sra", "srl",
        "subtype", "then", "to", "transport", "type", "unaffected", "units", "until", "use",
        "variable", "wait", "when", "while", "with", "xnor", "xor"};
    return r;
}

bool is_kw(const Token& t, const char* kw) { return t.kind == Tk::ident && t.lower == kw; }

/// A token that can end an operand, so that a following + or - is binary.
bool ends_operand(const Token& t) {
    if (t.kind == Tk::number || t.kind == Tk::chr || t.kind == Tk::str) return true;
    if (t.kind == Tk::ident) return !reserved().count(t.lower);
    return t.text == ")";
}

enum class Region { arch_decl, arch_stmt, proc_decl, proc_stmt, sub_decl, sub_stmt };

struct IfFrame {
    bool clocked_now = false;   ///< inside the branch taken on a clock edge
    bool reset_now = false;     ///< inside a reset branch
};

class Generator {
public:
    Generator(std::string file, const std::string& text) : file_(std::move(file)), text_(text), t_(tokenize(text)) {}

    std::vector<Mutant> run() {
        mark_skipped();
        walk();
        // file order, then class, then replacement; one mutant per distinct resulting text
        std::sort(out_.begin(), out_.end(), [](const Mutant& a, const Mutant& b) {
            return std::tie(a.offset, a.length, a.cls, a.replacement) <
                   std::tie(b.offset, b.length, b.cls, b.replacement);
        });
        std::vector<Mutant> unique;
        std::set<std::tuple<std::size_t, std::size_t, std::string>> seen;
        for (auto& m : out_) {
            if (m.replacement == m.original) continue;
            if (!seen.insert({m.offset, m.length, m.replacement}).second) continue;
            unique.push_back(std::move(m));
        }
        return unique;
    }

private:
    std::string file_;
    const std::string& text_;
    std::vector<Token> t_;
    std::vector<bool> skip_;
    std::vector<Mutant> out_;

    // Verification-only code of the design (the observation port) is not mutated: the
    // generate blocks `observed`/`not_observed` and the functions sizing that port.
    void mark_skipped() {
        static const std::set<std::string> units = {"observed", "not_observed", "obs_width", "sel_width"};
        skip_.assign(t_.size(), false);
        for (std::size_t i = 0; i < t_.size(); ++i) {
            if (t_[i].kind != Tk::ident || !units.count(t_[i].lower)) continue;
            const bool label = i + 1 < t_.size() && t_[i + 1].text == ":";
            const bool func = i > 0 && (is_kw(t_[i - 1], "function") || is_kw(t_[i - 1], "procedure"));
            if (!label && !func) continue;
            std::size_t j = i + 1;
            for (; j + 1 < t_.size(); ++j) {
                if (!is_kw(t_[j], "end")) continue;
                const Token& k = t_[j + 1];
                if (func && (is_kw(k, "function") || is_kw(k, "procedure") || k.lower == t_[i].lower)) break;
                if (label && is_kw(k, "generate") && j + 2 < t_.size() && t_[j + 2].lower == t_[i].lower) break;
            }
            for (std::size_t k = i; k <= j && k < t_.size(); ++k) skip_[k] = true;
        }
    }

    void add(MutantClass c, std::size_t first_tok, std::size_t last_tok, std::string repl) {
        if (skip_[first_tok]) return;
        Mutant m;
        m.file = file_;
        m.cls = c;
        m.offset = t_[first_tok].offset;
        m.length = t_[last_tok].offset + t_[last_tok].length - m.offset;
        m.line = t_[first_tok].line;
        m.column = t_[first_tok].column;
        m.original = text_.substr(m.offset, m.length);
        m.replacement = std::move(repl);
        out_.push_back(std::move(m));
    }
    void add_token(MutantClass c, std::size_t i, std::string repl) { add(c, i, i, std::move(repl)); }

    std::string span(std::size_t a, std::size_t b) const {
        return text_.substr(t_[a].offset, t_[b].offset + t_[b].length - t_[a].offset);
    }

    /// Index of the token closing the parenthesis opened at `open`.
    std::size_t matching_paren(std::size_t open) const {
        int depth = 0;
        for (std::size_t j = open; j < t_.size(); ++j) {
            if (t_[j].text == "(") ++depth;
            else if (t_[j].text == ")" && --depth == 0) return j;
        }
        return t_.size() - 1;
    }

    /// First token at parenthesis depth 0 from `from` whose text or keyword is in `stops`.
    std::size_t find_at_depth0(std::size_t from, const std::set<std::string>& stops) const {
        int depth = 0;
        for (std::size_t j = from; j < t_.size(); ++j) {
            if (t_[j].text == "(") ++depth;
            else if (t_[j].text == ")") --depth;
            else if (depth == 0 && stops.count(t_[j].kind == Tk::ident ? t_[j].lower : t_[j].text)) return j;
            if (depth < 0) return j;
        }
        return t_.size();
    }

    bool mentions_clock_edge(std::size_t a, std::size_t b) const {
        for (std::size_t j = a; j <= b && j < t_.size(); ++j)
            if (t_[j].lower == "event" || t_[j].lower == "rising_edge" || t_[j].lower == "falling_edge") return true;
        return false;
    }
    bool mentions_reset(std::size_t a, std::size_t b) const {
        for (std::size_t j = a; j <= b && j < t_.size(); ++j)
            if (t_[j].kind == Tk::ident && (t_[j].lower == "rst" || t_[j].lower == "reset")) return true;
        return false;
    }

    void number_mutants(std::size_t i) {
        const std::string& s = t_[i].text;
        if (s.find_first_not_of("0123456789") != std::string::npos) return;   // based, real, with _
        const long n = std::stol(s);
        add_token(MutantClass::literal, i, std::to_string(n + 1));
        if (n > 0) add_token(MutantClass::literal, i, std::to_string(n - 1));
    }

    /// +1 / -1 of an operand span [a, b] (a single literal is left to the literal class).
    void plus_minus_one(MutantClass c, std::size_t a, std::size_t b) {
        if (a > b || b >= t_.size()) return;
        if (a == b && t_[a].kind == Tk::number) return;
        const std::string e = span(a, b);
        const bool simple = a == b;
        add(c, a, b, (simple ? e : "(" + e + ")") + " + 1");
        add(c, a, b, (simple ? e : "(" + e + ")") + " - 1");
    }

    void condition_mutants(std::size_t a, std::size_t b, bool enable_candidate) {
        if (a > b || b >= t_.size()) return;
        add(MutantClass::negate, a, b, "not (" + span(a, b) + ")");
        if (enable_candidate) add(MutantClass::enable, a, b, "true");
        static const std::map<std::string, std::vector<std::string>> rel = {
            {"<", {"<="}}, {"<=", {"<"}}, {">", {">="}}, {">=", {">"}}, {"=", {"/="}}, {"/=", {"="}}};
        for (std::size_t j = a; j <= b; ++j) {
            if (t_[j].kind != Tk::op) continue;
            auto it = rel.find(t_[j].text);
            if (it == rel.end()) continue;
            for (const auto& r : it->second) add_token(MutantClass::rel, j, r);
        }
    }

    // The mutants of the operators and operands at token i: + and - swapped, * to +, numbers,
    // logic operators, range bounds, resize widths and shift amounts.
    void operand_mutants(std::size_t i) {
        const Token& tk = t_[i];
        if (tk.kind == Tk::op && (tk.text == "+" || tk.text == "-") && i > 0 && ends_operand(t_[i - 1])) {
            add_token(MutantClass::arith, i, tk.text == "+" ? "-" : "+");
        } else if (tk.kind == Tk::op && tk.text == "*") {
            add_token(MutantClass::arith, i, "+");
        } else if (tk.kind == Tk::number) {
            number_mutants(i);
        }
        static const std::map<std::string, std::string> logic = {
            {"and", "or"}, {"or", "and"}, {"nand", "nor"}, {"nor", "nand"}, {"xor", "xnor"}, {"xnor", "xor"}};
        if (tk.kind == Tk::ident && logic.count(tk.lower)) add_token(MutantClass::logic, i, logic.at(tk.lower));

        if (tk.text == "(") {   // a range inside parentheses: its bounds
            const std::size_t close = matching_paren(i);
            const std::size_t dir = find_at_depth0(i + 1, {"downto", "to", ")"});
            if (dir < close && (is_kw(t_[dir], "downto") || is_kw(t_[dir], "to"))) {
                const std::size_t a_end = dir - 1;
                std::size_t a_begin = i + 1;
                // the left bound starts after the last top-level comma before `downto`
                for (std::size_t j = find_at_depth0(i + 1, {",", "downto", "to"}); j < dir;
                     j = find_at_depth0(j + 1, {",", "downto", "to"}))
                    if (t_[j].text == ",") a_begin = j + 1;
                const std::size_t b_end = find_at_depth0(dir + 1, {",", "=>", ")", "|"}) - 1;
                plus_minus_one(MutantClass::slice, a_begin, a_end);
                plus_minus_one(MutantClass::slice, dir + 1, std::min(b_end, close - 1));
            }
        }
        if (tk.kind == Tk::ident && i + 1 < t_.size() && t_[i + 1].text == "(") {
            const std::size_t close = matching_paren(i + 1);
            const std::size_t comma = find_at_depth0(i + 2, {","});
            if (comma < close) {
                if (tk.lower == "resize") {
                    const std::size_t a = comma + 1, b = close - 1;
                    if (!(a == b && t_[a].kind == Tk::number) && a <= b)
                        add(MutantClass::resize, a, b, (a == b ? span(a, b) : "(" + span(a, b) + ")") + " - 1");
                } else if (tk.lower == "shift_left" || tk.lower == "shift_right") {
                    plus_minus_one(MutantClass::shift, comma + 1, close - 1);
                }
            }
        }
        static const std::set<std::string> shift_ops = {"sll", "srl", "sla", "sra", "rol", "ror"};
        if (tk.kind == Tk::ident && shift_ops.count(tk.lower) && i + 1 < t_.size()) {
            if (t_[i + 1].kind == Tk::number) {
                const long n = std::stol(t_[i + 1].text);
                add_token(MutantClass::shift, i + 1, std::to_string(n + 1));
                if (n > 0) add_token(MutantClass::shift, i + 1, std::to_string(n - 1));
            } else {
                plus_minus_one(MutantClass::shift, i + 1, i + 1);
            }
        }
    }

    // function-length: a token state machine; the statement structure, the conditions and the
    // register assignments are states one pass over the tokens changes, read in that order
    void walk() {
        std::vector<Region> stack;
        std::vector<IfFrame> ifs;                         // if-statements of the current process
        std::map<std::string, std::string> reset_value;   // target -> reset expression (process)
        auto stmt_region = [&] {
            return !stack.empty() && (stack.back() == Region::arch_stmt || stack.back() == Region::proc_stmt ||
                                      stack.back() == Region::sub_stmt);
        };
        auto in_process = [&] { return !stack.empty() && stack.back() == Region::proc_stmt; };
        auto clocked = [&] {
            return std::any_of(ifs.begin(), ifs.end(), [](const IfFrame& f) { return f.clocked_now; });
        };
        auto resetting = [&] {
            return std::any_of(ifs.begin(), ifs.end(), [](const IfFrame& f) { return f.reset_now; });
        };
        static const std::set<std::string> inner_end = {"if", "case", "loop", "generate", "block", "record",
                                                        "units", "component", "protected"};
        std::size_t stmt_start = 0;   // first token of the current statement
        std::size_t cond_until = 0;   // last token of the condition being read (0: none)
        bool in_cond_assign = false;  // inside `x <= a when c else b;`
        static const std::set<std::string> stmt_openers = {";", "then", "else", "begin", "loop", "generate", "=>"};

        for (std::size_t i = 0; i < t_.size(); ++i) {
            const Token& tk = t_[i];
            const std::string key = tk.kind == Tk::ident ? tk.lower : tk.text;
            const bool after_end = i > 0 && is_kw(t_[i - 1], "end");

            // ---- structure -------------------------------------------------------------
            if (key == "architecture" && !after_end) {
                stack.push_back(Region::arch_decl);
                continue;
            }
            if ((key == "process") && !after_end) {
                stack.push_back(Region::proc_decl);
                ifs.clear();
                reset_value.clear();
                continue;
            }
            if ((key == "function" || key == "procedure") && !after_end) {
                // a body follows when `is` comes before `;` (at depth 0 after the parameters)
                const std::size_t j = find_at_depth0(i + 1, {"is", ";"});
                if (j < t_.size() && is_kw(t_[j], "is")) stack.push_back(Region::sub_decl);
                continue;
            }
            if (key == "begin") {
                if (!stack.empty()) {
                    if (stack.back() == Region::arch_decl) stack.back() = Region::arch_stmt;
                    else if (stack.back() == Region::proc_decl) stack.back() = Region::proc_stmt;
                    else if (stack.back() == Region::sub_decl) stack.back() = Region::sub_stmt;
                }
                stmt_start = i + 1;
                continue;
            }
            if (key == "end") {
                const std::string next = i + 1 < t_.size() ? t_[i + 1].lower : "";
                if (next == "if") {
                    if (!ifs.empty()) ifs.pop_back();
                } else if (!inner_end.count(next) && !stack.empty()) {
                    stack.pop_back();
                }
                if (i + 1 < t_.size() && t_[i + 1].kind == Tk::ident) ++i;   // `end if`, `end process` ...
                continue;
            }
            if (!stmt_region()) continue;
            if (stmt_openers.count(key)) stmt_start = i + 1;

            // ---- conditions ------------------------------------------------------------
            if (key == "if" || key == "elsif" || key == "while") {
                const std::size_t term = find_at_depth0(i + 1, {"then", "loop", "generate"});
                if (term >= t_.size()) continue;
                const bool is_generate = is_kw(t_[term], "generate");
                const bool edge = mentions_clock_edge(i + 1, term - 1);
                if (in_process() && !is_generate) {
                    if (key == "if") ifs.push_back({});
                    if (!ifs.empty() && key != "while") {
                        ifs.back().clocked_now = edge;
                        ifs.back().reset_now = !edge && ifs.size() == 1 && mentions_reset(i + 1, term - 1);
                    }
                }
                const bool enable = key == "if" && in_process() && clocked() && !edge;
                condition_mutants(i + 1, term - 1, enable);
                cond_until = term;   // its operands are still mutated below; `<=` there compares
                continue;
            }
            if (key == ";") in_cond_assign = false;
            if (key == "else" && in_process() && !ifs.empty() && !in_cond_assign) {
                // an else of an if-statement (conditional assignments end at ';' instead)
                ifs.back().clocked_now = false;
                ifs.back().reset_now = false;
                stmt_start = i + 1;
                continue;
            }
            if (key == "when") {
                const std::size_t term = find_at_depth0(i + 1, {"=>", "else", ";"});
                if (term < t_.size() && t_[term].text != "=>") {   // not a case choice
                    condition_mutants(i + 1, term - 1, false);
                    cond_until = term;
                    in_cond_assign = true;
                }
                continue;
            }

            // ---- assignments: the register stuck at its reset value --------------------
            if (tk.text == "<=" && in_process() && stmt_start < i && i > cond_until) {
                const std::size_t semi = find_at_depth0(i + 1, {";"});
                if (semi < t_.size() && semi > i + 1) {
                    const std::string target = to_lower(span(stmt_start, i - 1));
                    const std::string value = span(i + 1, semi - 1);
                    if (resetting()) {
                        reset_value.emplace(target, value);
                    } else if (clocked()) {
                        auto it = reset_value.find(target);
                        if (it != reset_value.end()) add(MutantClass::stuck, i + 1, semi - 1, it->second);
                    }
                }
            }

            operand_mutants(i);
        }
    }
};

}  // namespace

const char* class_name(MutantClass c) {
    switch (c) {
        case MutantClass::arith: return "arith";
        case MutantClass::rel: return "rel";
        case MutantClass::logic: return "logic";
        case MutantClass::negate: return "negate";
        case MutantClass::literal: return "literal";
        case MutantClass::slice: return "slice";
        case MutantClass::resize: return "resize";
        case MutantClass::shift: return "shift";
        case MutantClass::stuck: return "stuck";
        case MutantClass::enable: return "enable";
    }
    return "?";
}

const std::vector<MutantClass>& all_classes() {
    static const std::vector<MutantClass> v = {MutantClass::arith,   MutantClass::rel,   MutantClass::logic,
                                               MutantClass::negate,  MutantClass::literal, MutantClass::slice,
                                               MutantClass::resize,  MutantClass::shift, MutantClass::stuck,
                                               MutantClass::enable};
    return v;
}

std::string Mutant::name() const {
    return file + ":" + std::to_string(line) + ":" + std::to_string(column) + " " + class_name(cls) + " `" +
           original + "` -> `" + replacement + "`";
}

std::string Mutant::apply(const std::string& text) const {
    if (offset + length > text.size() || text.compare(offset, length, original) != 0)
        throw std::invalid_argument("mutant " + name() + " does not match the text it is applied to");
    std::string r = text;
    r.replace(offset, length, replacement);
    return r;
}

std::vector<Mutant> generate_mutants(const std::string& file, const std::string& text) {
    return Generator(file, text).run();
}

}  // namespace hc::mutation
