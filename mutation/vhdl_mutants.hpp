// vhdl_mutants.hpp: every single-point mutant of a VHDL design file, generated mechanically.
//
// A careful tokenizer (not a full VHDL parser) reads a design file and finds, in the
// statement parts of architectures and of subprogram bodies (never in declarations, ports,
// generics or comments), every place where one of these edits applies:
//   arith     binary + <-> -, and * -> +
//   rel       in a condition: < <-> <=, > <-> >=, = <-> /= (the off-by-one and equality
//             neighbours)
//   logic     in a condition: and <-> or, nand <-> nor, xor <-> xnor
//   negate    every if/elsif/when condition C -> not (C)
//   literal   an integer literal N -> N + 1 and (N > 0) N - 1
//   slice     a bound B of a (A downto B) / (A to B) range -> (B) + 1 and (B) - 1
//   resize    resize(X, W) -> resize(X, W - 1)
//   shift     shift_left/shift_right(X, N) and sll/srl/sla/sra/rol/ror N -> N + 1, N - 1
//   stuck     an assignment r <= E in the clocked branch of a process whose reset branch
//             assigns r <= R -> r <= R (the register stuck at its reset value)
//   enable    an `if` condition inside a clocked branch (not the clock test itself) -> true
//             (the register's enable forced on)
// A mutant is one edit: a byte range of the original text and its replacement. Mutants are
// listed in file order (offset, then class, then replacement); two edits that produce the
// same text are one mutant (the first listed keeps its class). The list is deterministic.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace hc::mutation {

enum class MutantClass { arith, rel, logic, negate, literal, slice, resize, shift, stuck, enable };

/// The class's name as used in reports and mutant ids ("arith", "rel", ...).
const char* class_name(MutantClass c);
/// All classes, in report order.
const std::vector<MutantClass>& all_classes();

struct Mutant {
    std::string file;          ///< file name as given to generate_mutants
    int line = 0, column = 0;  ///< 1-based position of the edit's first character
    MutantClass cls{};
    std::size_t offset = 0;    ///< byte offset of the edited range in the original text
    std::size_t length = 0;    ///< its length
    std::string original;      ///< the original text of the range
    std::string replacement;   ///< what replaces it
    /// "file:line:column class `original` -> `replacement`": a stable, readable name.
    std::string name() const;
    /// The design file's text with this mutant applied.
    std::string apply(const std::string& text) const;
};

/// Every mutant of one design file's text.
std::vector<Mutant> generate_mutants(const std::string& file, const std::string& text);

}  // namespace hc::mutation
