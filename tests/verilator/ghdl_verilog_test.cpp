// ghdl_verilog_test.cpp: GHDL's bit-string constants read as sized literals (cosim/ghdl_verilog.hpp):
// the rewrite on hand-written text ([model]), its shell filter, and find_max's netlist at a
// 38-bit response as GHDL writes it and as the readers get it ([ghdl], needs GHDL).
#include <catch2/catch.hpp>

#include <string>

#include "cosim/cosim.hpp"
#include "cosim/ghdl_verilog.hpp"
#include "model/util/util.hpp"

namespace fs = std::filesystem;
using namespace hc;

namespace {

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

}  // namespace

TEST_CASE("bit strings become sized binary literals of their length, other strings stay", "[model][verilator]") {
    using cosim::sized_bit_literals;
    CHECK(sized_bit_literals("assign x = \"1000\";") == "assign x = 4'b1000;");
    CHECK(sized_bit_literals("\"0\" \"1\"") == "1'b0 1'b1");
    const std::string wide = "1" + std::string(37, '0');
    CHECK(sized_bit_literals("running = \"" + wide + "\";") == "running = 38'b" + wide + ";");
    // several on one line, and lines around them untouched
    CHECK(sized_bit_literals("a\n  assign y = c ? \"101\" : \"0011\"; // mux\nb") ==
          "a\n  assign y = c ? 3'b101 : 4'b0011; // mux\nb");
    // not binary: another character, empty, or a quote without its end
    CHECK(sized_bit_literals("$display(\"x=%d\", \"10x1\", \"\");") == "$display(\"x=%d\", \"10x1\", \"\");");
    CHECK(sized_bit_literals("\"1z\" then \"01\"") == "\"1z\" then 2'b01");
    CHECK(sized_bit_literals("x = \"101") == "x = \"101");
    CHECK(sized_bit_literals("") == "");
}

TEST_CASE("the shell filter rewrites as sized_bit_literals does", "[model][verilator]") {
    const util::ScratchDir dir;
    const std::string text = "assign a = \"" + std::string(40, '1') + "\"; assign b = c ? \"01\" : \"1x\";\n"
                             "$display(\"x=%d\", \"\");\nassign d = \"0\";\n";
    util::write_file_atomic(dir.path() / "in.v", text);
    REQUIRE(util::run_process({"sh", "-c", std::string(cosim::kSizedBitLiteralsFilter) + " < in.v > out.v"}, {.cwd = dir.path()}) == 0);
    CHECK(util::read_file(dir.path() / "out.v") == cosim::sized_bit_literals(text));
    CHECK(util::read_file(dir.path() / "out.v") != text);
}

TEST_CASE("synth_verilog rewrites the command's output, and leaves a failed command's as it is", "[model][verilator]") {
    const util::ScratchDir dir;
    const fs::path v = dir.path() / "x.v";
    CHECK(cosim::synth_verilog({"sh", "-c", "printf 'assign n = \"110\";\\n'"}, v, {.log = dir.path() / "log"}) == 0);
    CHECK(util::read_file(v) == "assign n = 3'b110;\n");
    CHECK(cosim::synth_verilog({"sh", "-c", "printf 'assign n = \"110\";\\n'; exit 3"}, v, {.log = dir.path() / "log"}) == 3);
    CHECK(util::read_file(v) == "assign n = \"110\";\n");
}

TEST_CASE("find_max at RESP_W 38: GHDL writes four bit strings, the readers get four 38-bit literals", "[ghdl]") {
    const util::ScratchDir dir;
    std::vector<std::string> argv = {"ghdl", "--synth", "--std=08", "--workdir=" + dir.path().string(), "-gRESP_W=38", "--out=verilog"};
    for (const auto& s : cosim::rtl_sources()) argv.push_back(s.string());
    argv.insert(argv.end(), {"-e", "find_max"});
    REQUIRE(util::run_process(argv, {.log = dir.path() / "raw.log", .stdout_file = dir.path() / "raw.v"}) == 0);
    const std::string raw = util::read_file(dir.path() / "raw.v");
    const std::string most_negative = "1" + std::string(37, '0');
    CHECK(count(raw, "\"" + most_negative + "\"") == 4);
    REQUIRE(cosim::synth_verilog(argv, dir.path() / "find_max.v", {.log = dir.path() / "synth.log"}) == 0);
    const std::string sized = util::read_file(dir.path() / "find_max.v");
    CHECK(count(sized, "38'b" + most_negative) == 4);
    CHECK(sized.find('"') == std::string::npos);
    CHECK(sized == cosim::sized_bit_literals(raw));
}
