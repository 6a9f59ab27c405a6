// harris_top.cpp: HarrisTop chooses its instance of the cycle model (harris/harris_top_t.hpp):
// the one compiled for its Formats when kCompiledFormats (generated from sweep/configs/*.json)
// lists them, else the one that reads the widths at run time.
#include "model/harris/harris_top.hpp"

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "harris/compiled_formats.hpp"
#include "model/harris/harris_top_t.hpp"

namespace hc {

namespace {

using Factory = std::unique_ptr<CycleModel> (*)(const Geometry&);

template <std::size_t I>
std::unique_ptr<CycleModel> make_compiled(const Geometry& g) {
    using FS = StaticFormats<kCompiledFormats[I]>;
    return std::make_unique<HarrisTopT<FS>>(g, FS{});
}

template <std::size_t... I>
constexpr std::array<Factory, sizeof...(I)> compiled_factories(std::index_sequence<I...>) {
    return {&make_compiled<I>...};
}

constexpr auto kFactories = compiled_factories(std::make_index_sequence<kCompiledFormats.size()>{});

/// The index in kCompiledFormats of these formats, or -1.
int compiled_index(const Formats& f) {
    for (std::size_t i = 0; i < kCompiledFormats.size(); ++i)
        if (kCompiledFormats[i] == f) return static_cast<int>(i);
    return -1;
}

}  // namespace

bool has_compiled_instance(const Formats& f) { return compiled_index(f) >= 0; }

std::vector<Formats> compiled_formats() { return {kCompiledFormats.begin(), kCompiledFormats.end()}; }

HarrisTop::HarrisTop(const Geometry& g, const Formats& f, Specialisation s) : g_(g), f_(f) {
    g_.validate();
    f_.validate();
    const int i = s == Specialisation::compiled_if_any ? compiled_index(f_) : -1;
    compiled_ = i >= 0;
    if (compiled_)
        m_ = kFactories[static_cast<std::size_t>(i)](g_);
    else
        m_ = std::make_unique<HarrisTopT<DynamicFormats>>(g_, DynamicFormats{f_});
}

namespace {
/// What a state image belongs to: geometry, formats and instance.
std::string state_key(const Geometry& g, const Formats& f, bool compiled) {
    return "harris_top " + std::to_string(g.width) + "x" + std::to_string(g.height) + " formats " +
           std::to_string(formats_hash(f)) + (compiled ? " compiled" : " run-time") + "\n";
}
}  // namespace

std::string HarrisTop::save_state() const { return state_key(g_, f_, compiled_) + m_->state(); }

void HarrisTop::restore_state(const std::string& image) {
    const std::string key = state_key(g_, f_, compiled_);
    if (image.compare(0, key.size(), key) != 0)
        throw std::invalid_argument("the cycle model state belongs to another geometry, formats or instance (expected '" +
                                    key.substr(0, key.size() - 1) + "')");
    m_->restore(image.substr(key.size()));
}

}  // namespace hc
