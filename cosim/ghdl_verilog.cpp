// ghdl_verilog.cpp: GHDL's bit-string constants as sized literals; GHDL's synthesis to Verilog.
#include "cosim/ghdl_verilog.hpp"

namespace hc::cosim {

std::string sized_bit_literals(const std::string& verilog) {
    std::string out;
    out.reserve(verilog.size());
    size_t at = 0;
    for (size_t q = verilog.find('"'); q != std::string::npos; q = verilog.find('"', at)) {
        const size_t end = verilog.find('"', q + 1);
        if (end == std::string::npos) break;
        const std::string bits = verilog.substr(q + 1, end - q - 1);
        const bool binary = !bits.empty() && bits.find_first_not_of("01") == std::string::npos;
        out += verilog.substr(at, q - at);
        out += binary ? std::to_string(bits.size()) + "'b" + bits : verilog.substr(q, end - q + 1);
        at = end + 1;
    }
    return out + verilog.substr(at);
}

const char* const kSizedBitLiteralsFilter = R"(perl -pe "s/\"([01]+)\"/length(\$1).\"'b\$1\"/ge")";

const char* const kVerilogReading = "GHDL bit strings as sized literals";

int synth_verilog(const std::vector<std::string>& argv, const std::filesystem::path& verilog, util::ProcessOptions opt) {
    opt.stdout_file = verilog;
    const int rc = util::run_process(argv, opt);
    if (rc == 0) util::write_file_atomic(verilog, sized_bit_literals(util::read_file(verilog)));
    return rc;
}

}  // namespace hc::cosim
