// formats_json.hpp: the one reader and writer of Formats as JSON, derived from the field
// table (format_fields() in harris_pkg.hpp). `--config FILE.json`, sweep specs and the
// co-simulation's run configuration all go through it.
//
// JSON form: an object {"sobel_w": 11, "m_drop": 5, ...}; a missing key keeps the value the
// caller starts from (the thesis's by default); "name" is allowed and ignored; any other key
// is an error that lists the known ones.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "model/harris/harris_pkg.hpp"
#include "model/util/errors.hpp"

namespace hc {

/// The fields of `table` as a JSON object, in table order; "name" first when not empty.
template <class S, std::size_t N>
nlohmann::ordered_json fields_to_json(const S& f, const std::array<FieldOf<S>, N>& table, const std::string& name = "") {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    if (!name.empty()) j["name"] = name;
    for (const auto& fld : table) j[fld.name] = f.*(fld.member);
    return j;
}

/// The known keys of `table`, for error messages ("sobel_w, m_prod_w, ...").
template <class S, std::size_t N>
std::string field_names(const std::array<FieldOf<S>, N>& table) {
    std::string s;
    for (const auto& fld : table) {
        if (!s.empty()) s += ", ";
        s += fld.name;
    }
    return s;
}

/// Applies the keys of the JSON object `j` to `f` (other fields keep their values). Throws
/// InputError "<what>: ..." naming the offending key. Does not validate the result.
template <class S, std::size_t N, class Json>
void apply_fields(const Json& j, S& f, const std::array<FieldOf<S>, N>& table, const std::string& what) {
    if (!j.is_object()) throw InputError(what + ": must be a JSON object of format keys (" + field_names(table) + ")");
    for (auto it = j.begin(); it != j.end(); ++it) {
        if (it.key() == "name") continue;
        const FieldOf<S>* fld = nullptr;
        for (const auto& x : table)
            if (it.key() == x.name) fld = &x;
        if (!fld) throw InputError(what + ": unknown key '" + it.key() + "' (format keys: " + field_names(table) + ")");
        const auto& v = it.value();
        if (!v.is_number_integer() || v.template get<long long>() < -1000000 || v.template get<long long>() > 1000000)
            throw InputError(what + "." + it.key() + ": must be an integer of at most a million, not " + v.dump());
        f.*(fld->member) = static_cast<int>(v.template get<long long>());
    }
}

/// Formats as JSON text (2-space indent, newline-terminated), "name" first when given.
std::string formats_to_json(const Formats& f, const std::string& name = "");

/// Formats from a parsed JSON object over `base` (the thesis's by default), validated.
/// Throws InputError "<what>: ..." for bad JSON, unknown keys, non-integers or formats the
/// design cannot be built with.
Formats formats_from_json(const nlohmann::json& j, const std::string& what, const Formats& base = {});
/// The same from JSON text.
Formats formats_from_json_text(const std::string& text, const std::string& what);

/// Formats from a JSON file (`--config FILE.json`); errors name the file as "--config '<path>'".
Formats formats_from_file(const std::string& path);

/// Formats::validate() with its message as InputError "<what>: ..." (user input boundary).
void validate_input(const Formats& f, const std::string& what);

}  // namespace hc
