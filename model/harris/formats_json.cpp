// formats_json.cpp: see formats_json.hpp.
#include "model/harris/formats_json.hpp"

#include "model/util/util.hpp"

namespace hc {

std::string formats_to_json(const Formats& f, const std::string& name) {
    return fields_to_json(f, format_fields(), name).dump(2) + "\n";
}

void validate_input(const Formats& f, const std::string& what) {
    try {
        f.validate();
    } catch (const std::invalid_argument& e) {
        throw InputError(what + ": " + e.what());
    }
}

Formats formats_from_json(const nlohmann::json& j, const std::string& what, const Formats& base) {
    Formats f = base;
    apply_fields(j, f, format_fields(), what);
    validate_input(f, what);
    return f;
}

Formats formats_from_json_text(const std::string& text, const std::string& what) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(what + ": not valid JSON: " + e.what());
    }
    return formats_from_json(j, what);
}

Formats formats_from_file(const std::string& path) {
    const std::string what = "--config '" + path + "'";
    return formats_from_json_text(util::read_file(path, what), what);
}

}  // namespace hc
