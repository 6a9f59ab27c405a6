// mutated_rtl.hpp: a copy of the project's rtl/ with one text replaced, for the proofs' tests
// that must fail on changed VHDL.
#pragma once

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "model/util/util.hpp"

/// A copy of rtl/ in `dir` with `from` replaced by `to` in `file` (which must hold it once).
inline std::filesystem::path mutated_rtl(const std::filesystem::path& dir, const std::string& file, const std::string& from,
                                         const std::string& to) {
    namespace fs = std::filesystem;
    const fs::path rtl = dir / "rtl";
    fs::create_directories(rtl);
    for (const auto& e : fs::directory_iterator(HC_SOURCE_DIR "/rtl")) fs::copy_file(e.path(), rtl / e.path().filename());
    std::string vhdl = hc::util::read_file(rtl / file);
    const size_t at = vhdl.find(from);
    REQUIRE(at != std::string::npos);
    REQUIRE(vhdl.find(from, at + 1) == std::string::npos);
    vhdl.replace(at, from.size(), to);
    hc::util::write_file_atomic(rtl / file, vhdl);
    return rtl;
}
