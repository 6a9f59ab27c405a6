// vhdl_agreement_test.cpp: the VHDL restates nothing the C++ owns without a check here.
//
//   - rtl/harris_pkg.vhd's DEF_* defaults equal the table of formats (harris_pkg.hpp):
//     names, VHDL subtypes and values; no DEF_* outside the table but the image size;
//   - harris_top's generics are IMG_WIDTH, IMG_HEIGHT, the table's generics in order, OBSERVE,
//     each defaulting to its DEF_* constant;
//   - the observation port: the `pack` process of harris_top puts the registers in the order
//     of obs_layout() (model/harris/observation.cpp), and harris_pkg's obs_width() adds up to
//     the C++ obs_width() for the thesis's and for other formats.
// Each check is a function of the VHDL text, so the test also shows it fails on a drifted copy.
#include <catch2/catch.hpp>

#include <map>
#include <regex>
#include <sstream>

#include "model/harris/harris_pkg.hpp"
#include "model/harris/observation.hpp"
#include "model/util/util.hpp"

using namespace hc;

namespace {

std::string rtl(const std::string& file) { return util::read_file(std::string(HC_SOURCE_DIR) + "/rtl/" + file); }

/// Differences between the DEF_* constants of a harris_pkg text and the table ("" if none).
std::string defaults_drift(const std::string& pkg) {
    static const std::regex def(R"(constant\s+DEF_(\w+)\s*:\s*(positive|natural)\s*:=\s*(\d+)\s*;)", std::regex::icase);
    std::map<std::string, std::pair<std::string, long>> vhdl;
    for (auto it = std::sregex_iterator(pkg.begin(), pkg.end(), def); it != std::sregex_iterator(); ++it)
        vhdl[(*it)[1]] = {(*it)[2], std::stol((*it)[3])};
    std::string out;
    const Geometry g{};
    for (const auto& [name, value] : std::vector<std::pair<std::string, long>>{{"IMG_WIDTH", g.width}, {"IMG_HEIGHT", g.height}})
        if (!vhdl.count(name) || vhdl[name].second != value) out += "DEF_" + name + " differs from Geometry{}; ";
    for (const auto& f : format_fields()) {
        const auto it = vhdl.find(f.generic);
        if (it == vhdl.end()) out += std::string("DEF_") + f.generic + " missing; ";
        else if (it->second.second != f.default_value())
            out += std::string("DEF_") + f.generic + " = " + std::to_string(it->second.second) + " but the table says " +
                   std::to_string(f.default_value()) + "; ";
        else if (it->second.first != f.vhdl_type)
            out += std::string("DEF_") + f.generic + " is " + it->second.first + ", the table says " + f.vhdl_type + "; ";
    }
    // the testbenches take their generic lists from the DEF_* constants in file order
    // (tools/cmake/vhdl_generics.cmake): that order must be generics()'s
    std::vector<std::string> order, want;
    for (auto it = std::sregex_iterator(pkg.begin(), pkg.end(), def); it != std::sregex_iterator(); ++it)
        order.push_back((*it)[1]);
    for (const auto& [name, value] : generics(g, Formats{})) want.push_back(name);
    if (order != want && out.empty()) out += "DEF_* constants are not in the order of generics(); ";
    for (const auto& [name, v] : vhdl) {
        bool known = name == "IMG_WIDTH" || name == "IMG_HEIGHT";
        for (const auto& f : format_fields()) known |= name == f.generic;
        if (!known) out += "DEF_" + name + " is not in the table; ";
    }
    return out;
}

/// The put(...) arguments of the `pack` process, as signal names, in order.
std::vector<std::string> pack_order(const std::string& top) {
    const auto a = top.find("p := 0;", top.find("pack : process"));   // after the put procedures
    const auto b = top.find("end process pack", a);
    REQUIRE(a != std::string::npos);
    REQUIRE(b != std::string::npos);
    const std::string body = top.substr(a, b - a);
    static const std::regex put(R"(\bput\((?:std_ulogic_vector\()?(\w+))");
    std::vector<std::string> v;
    for (auto it = std::sregex_iterator(body.begin(), body.end(), put); it != std::sregex_iterator(); ++it)
        v.push_back((*it)[1]);
    return v;
}

/// harris_pkg's obs_width() body evaluated: a sum of products of integers and the names
/// PIXEL_W, sobel_w, m_w, bf_w, resp_w.
long vhdl_obs_width(const std::string& pkg, const Formats& f) {
    const auto a = pkg.find("function obs_width(sobel_w, m_w, bf_w, resp_w : positive) return positive is\n  begin");
    REQUIRE(a != std::string::npos);
    const auto r = pkg.find("return", a + 80);
    const auto e = pkg.find(';', r);
    std::string expr = pkg.substr(r + 6, e - r - 6);
    expr = std::regex_replace(expr, std::regex("--[^\n]*"), "");   // comments
    const std::map<std::string, long> names = {
        {"PIXEL_W", 8}, {"sobel_w", f.sobel_w}, {"m_w", f.m_w()}, {"bf_w", f.bf_w()}, {"resp_w", f.resp_w}};
    long sum = 0;
    std::stringstream terms(std::regex_replace(expr, std::regex("\\s+"), ""));
    for (std::string term; std::getline(terms, term, '+');) {
        long prod = 1;
        std::stringstream factors(term);
        for (std::string x; std::getline(factors, x, '*');) {
            if (names.count(x)) prod *= names.at(x);
            else prod *= std::stol(x);
        }
        sum += prod;
    }
    return sum;
}

}  // namespace

TEST_CASE("the VHDL defaults of harris_pkg equal the table of formats", "[model][vhdl]") {
    CHECK(defaults_drift(rtl("harris_pkg.vhd")) == "");
}

TEST_CASE("a drifted VHDL default is reported by name, value and the table's value", "[model][vhdl]") {
    std::string pkg = rtl("harris_pkg.vhd");
    pkg = std::regex_replace(pkg, std::regex(R"(DEF_M_DROP\s*:\s*natural\s*:=\s*5;)"), "DEF_M_DROP : natural := 6;");
    CHECK(defaults_drift(pkg) == "DEF_M_DROP = 6 but the table says 5; ");
    pkg = std::regex_replace(pkg, std::regex(R"(constant DEF_KTR_W[^\n]*\n)"), "");
    CHECK(defaults_drift(pkg) == "DEF_M_DROP = 6 but the table says 5; DEF_KTR_W missing; ");
}

TEST_CASE("harris_top's generics are the image size, the table's generics in order and OBSERVE", "[model][vhdl]") {
    const std::string top = rtl("harris_top.vhd");
    const auto a = top.find("entity harris_top is");
    const auto b = top.find("port (", a);
    const std::string decl = top.substr(a, b - a);
    static const std::regex gen(R"((\w+)\s*:\s*(positive|natural|boolean)\s*:=\s*(\w+))");
    std::vector<std::string> names;
    for (auto it = std::sregex_iterator(decl.begin(), decl.end(), gen); it != std::sregex_iterator(); ++it) {
        names.push_back((*it)[1]);
        if ((*it)[1] != "OBSERVE") CHECK((*it)[3] == "DEF_" + std::string((*it)[1]));
    }
    std::vector<std::string> want;
    for (const auto& [n, v] : generics(Geometry{}, Formats{})) want.push_back(n);
    want.push_back("OBSERVE");
    CHECK(names == want);
}

TEST_CASE("the pack process puts the registers in the order of obs_layout", "[model][vhdl]") {
    std::vector<std::string> want;
    for (const auto& f : obs_layout(Formats{})) want.push_back(f.name);
    std::vector<std::string> got = pack_order(rtl("harris_top.vhd"));
    // the corner port is packed from its internal driver corner_o
    REQUIRE(!got.empty());
    CHECK(got.back() == "corner_o");
    got.back() = "corner";
    CHECK(got == want);
}

TEST_CASE("harris_pkg's obs_width adds up to the C++ layout's width for several formats", "[model][vhdl]") {
    const std::string pkg = rtl("harris_pkg.vhd");
    Formats narrow;
    narrow.sobel_w = 9;
    narrow.m_prod_w = 17;
    narrow.bf_sum_w = 18;
    narrow.resp_w = 40;
    for (const Formats& f : {Formats{}, narrow}) {
        CHECK(vhdl_obs_width(pkg, f) == obs_width(f));
    }
    CHECK(obs_width(Formats{}) == 3259);   // the thesis's formats: the bits README.md quotes
}
