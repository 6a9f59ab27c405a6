// table.hpp: the lookups of a table of named rows (a struct with `id` and `name`), written once
// for every such table (the co-processor's corner sources, the landmark chain's corner sources
// and descriptors): a value's row, a name's value, the names in order.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/util/errors.hpp"

namespace hc::util {

/// The row of `id`; std::logic_error (an enum value without a row: a fault of the table) else.
template <class Row, class Id>
const Row& row_of(const std::vector<Row>& table, Id id, const char* what) {
    const auto it = std::find_if(table.begin(), table.end(), [id](const Row& r) { return r.id == id; });
    if (it == table.end()) throw std::logic_error(std::string(what) + " without a row in its table");
    return *it;
}

/// The names joined by ", " (with_help: each followed by its `help` in parentheses where it
/// has one), of the rows `keep` takes (null: all).
template <class Row>
std::string row_names(const std::vector<Row>& table, bool with_help = false, bool (*keep)(const Row&) = nullptr) {
    std::string out;
    for (const auto& r : table) {
        if (keep && !keep(r)) continue;
        if (!out.empty()) out += ", ";
        out += r.name;
        if (with_help && *r.help) out += std::string(" (") + r.help + ")";
    }
    return out;
}

/// The value of the row named `name`; InputError "unknown <what> '<name>' (one of: ...)" else.
template <class Row>
auto row_named(const std::vector<Row>& table, const std::string& name, const std::string& what) {
    for (const auto& r : table)
        if (name == r.name) return r.id;
    throw InputError("unknown " + what + " '" + name + "' (one of: " + row_names(table) + ")");
}

}  // namespace hc::util
