// hc_bridge.cpp: the extern "C" entry points of hc_bridge.h over one cosim::Session.
// Every entry point catches every exception: none may unwind into GHDL's runtime.
#include "cosim/hc_bridge.h"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "cosim/session.hpp"
#include "model/util/util.hpp"

namespace {
std::unique_ptr<hc::cosim::Session> g_session;
int g_status = 2;   // error until a session closes normally
std::vector<long> g_generics;   // handed over by hc_generic, in harris_pkg order

void fail(const char* where, const char* what) {
    std::fprintf(stderr, "harris-cosim bridge: %s: %s\n", where, what);
    std::fflush(stderr);
    g_status = 2;
}

// f()'s value, or none when it threw: the exception reported as `where`'s (fail).
template <class F>
std::optional<int32_t> guarded(const char* where, F f) {
    try {
        return f();
    } catch (const std::exception& e) {
        fail(where, e.what());
    } catch (...) {
        fail(where, "unknown exception");
    }
    return std::nullopt;
}
}  // namespace

extern "C" int32_t hc_generic(int32_t index, int32_t value) {
    if (index >= 0 && index < 64) {
        if (g_generics.size() <= static_cast<size_t>(index)) g_generics.resize(static_cast<size_t>(index) + 1, -1);
        g_generics[static_cast<size_t>(index)] = value;
    }
    return 0;
}

extern "C" int32_t hc_open(int32_t obs_w) {
    return guarded("hc_open", [&] {
               const char* path = std::getenv("HC_COSIM_CONFIG");
               if (!path || !*path) throw std::runtime_error("HC_COSIM_CONFIG is not set (run through 'harris-cosim rtl')");
               const std::string text = hc::util::read_file(path, std::string("run configuration '") + path + "'");
               auto s = std::make_unique<hc::cosim::Session>(hc::cosim::run_config_from_json(text));
               s->check_design(obs_w, g_generics);
               g_session = std::move(s);
               return 0;
           })
        .value_or(1);
}

extern "C" int32_t hc_next(void) {
    if (!g_session) return HC_CMD_END;
    const auto cmd = guarded("hc_next", [] {
        switch (g_session->next()) {
            case hc::cosim::Command::write: return HC_CMD_WRITE;
            case hc::cosim::Command::idle: return HC_CMD_IDLE;
            case hc::cosim::Command::end: return HC_CMD_END;
        }
        return HC_CMD_END;
    });
    if (cmd) return *cmd;
    g_session.reset();
    return HC_CMD_END;
}

extern "C" int32_t hc_data(void) {
    return g_session ? static_cast<int32_t>(g_session->data()) : 0;
}

extern "C" int32_t hc_observe(const uint8_t* obs) {
    if (!g_session) return 1;
    if (const auto r = guarded("hc_observe", [&] { return g_session->observe(obs) ? 1 : 0; })) return *r;
    g_session.reset();
    return 1;
}

extern "C" int32_t hc_observe_held(const uint8_t* obs, int32_t after_reset) {
    if (!g_session) return 1;
    if (const auto r = guarded("hc_observe_held", [&] { return g_session->observe_held(obs, after_reset != 0) ? 1 : 0; }))
        return *r;
    g_session.reset();
    return 1;
}

extern "C" int32_t hc_close(void) {
    if (!g_session) return g_status;
    guarded("hc_close", [] {
        g_status = g_session->close();
        return 0;
    });
    g_session.reset();
    std::fflush(stderr);
    return g_status;
}
