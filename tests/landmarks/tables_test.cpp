// The descriptor and corner-source tables (mapping/landmarks/descriptor_table.cpp, corners.cpp)
// are the one list of each: the enum follows them, names parse back, the norm comes from the
// Feature2D, the help texts of `landmarks` and `slam` and the docs' lists are made from them.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "mapping/landmarks/landmarks.hpp"
#include "model/util/util.hpp"

using namespace hc::landmarks;
namespace fs = std::filesystem;

namespace {

/// The first-column names (`name`) of the Markdown table under `heading` in docs/landmarks.md
/// whose header's first cell is `column`, in order.
std::vector<std::string> doc_list(const std::string& heading, const std::string& column) {
    std::ifstream in(fs::path(HC_SOURCE_DIR) / "docs" / "landmarks.md");
    REQUIRE(in.good());
    std::string line;
    bool in_section = false, in_table = false;
    std::vector<std::string> names;
    const std::regex row(R"(^\| `([^`]+)` \|)");
    while (std::getline(in, line)) {
        if (line.rfind("#", 0) == 0) {
            if (in_section) break;
            in_section = line.find(heading) != std::string::npos;
            continue;
        }
        if (!in_section) continue;
        if (line.rfind("| " + column + " |", 0) == 0) {
            in_table = true;
            continue;
        }
        std::smatch m;
        if (in_table && std::regex_search(line, m, row)) names.push_back(m[1]);
        else if (in_table && line.rfind("|---", 0) != 0) in_table = false;
    }
    return names;
}

/// `harris-cosim <command> --help`, as printed.
std::string help_of(const std::string& command) {
    const fs::path out = fs::temp_directory_path() / ("hc_tables_help_" + command + ".txt");
    hc::util::ProcessOptions o;
    o.stdout_file = out;
    REQUIRE(hc::util::run_process({HC_HARRIS_COSIM, command, "--help"}, o) == 0);
    std::string text = hc::util::read_file(out);
    fs::remove(out);
    return text;
}

}  // namespace

TEST_CASE("the descriptor and corner-source tables are the one list of each", "[tables]") {
    const auto& dt = descriptor_table();
    REQUIRE(dt.size() == 9);
    for (size_t i = 0; i < dt.size(); ++i) {
        INFO("descriptor row " << i << ": " << dt[i].name);
        CHECK(static_cast<size_t>(dt[i].id) == i);            // the enum in the table's order
        CHECK(parse_descriptor(dt[i].name) == dt[i].id);
        CHECK(descriptor_name(dt[i].id) == dt[i].name);
        const auto f = make_descriptor(dt[i].id);
        CHECK(descriptor_norm(dt[i].id) == f->defaultNorm());
        // a Hamming-matched descriptor is of bytes, an L2-matched one of floats
        CHECK(f->descriptorType() == (is_binary(dt[i].id) ? CV_8U : CV_32F));
        CHECK(default_ratio(dt[i].id) == dt[i].ratio);
    }
    CHECK_FALSE(is_binary(Descriptor::sift));
    CHECK(is_binary(Descriptor::orb));
    CHECK_THROWS_AS(check_combination(Descriptor::sift, Detector::opencv, Norm::hamming), hc::InputError);
    CHECK_THROWS_AS(check_combination(Descriptor::brief, Detector::opencv, Norm::l2), hc::InputError);
    CHECK_THROWS_WITH(parse_descriptor("surf"), Catch::Contains("surf") && Catch::Contains(descriptor_list()));
    CHECK(comparison_descriptors() == std::vector<Descriptor>{Descriptor::grid, Descriptor::sift, Descriptor::sift_ratio1,
                                                               Descriptor::orb, Descriptor::brisk, Descriptor::brief,
                                                               Descriptor::brief_gaussian, Descriptor::freak});
    CHECK(ReobservationOptions{}.descriptors == reobservation_descriptors());

    const auto& ct = detector_table();
    REQUIRE(ct.size() == 8);
    for (size_t i = 0; i < ct.size(); ++i) {
        INFO("corner source row " << i << ": " << ct[i].name);
        CHECK(static_cast<size_t>(ct[i].id) == i);
        CHECK(parse_detector(ct[i].name) == ct[i].id);
        CHECK(detector_name(ct[i].id) == ct[i].name);
        CHECK(is_hardware(ct[i].id) == (ct[i].detect == nullptr));
    }
    CHECK(all_detectors().size() == ct.size());
    CHECK(is_hardware(Detector::spec));
    CHECK(is_hardware(Detector::cycle));
    CHECK(is_hardware(Detector::rtl));
    CHECK_FALSE(is_hardware(Detector::orb));
    CHECK_THROWS_WITH(parse_detector("fast"), Catch::Contains("fast") && Catch::Contains(detector_list()));

    // keypoints of a foreign detector enter an octave-reading descriptor at octave 0
    std::vector<cv::KeyPoint> kp{cv::KeyPoint(10.f, 10.f, 7.f, 0.f, 0.f, 3)};
    CHECK(keypoints_for(Descriptor::orb, Detector::sift, kp)[0].octave == 0);
    CHECK(keypoints_for(Descriptor::orb, Detector::orb, kp)[0].octave == 3);
    CHECK(keypoints_for(Descriptor::sift, Detector::sift512, kp)[0].octave == 3);
    CHECK(keypoints_for(Descriptor::brief, Detector::sift, kp)[0].octave == 3);
}

TEST_CASE("the help texts of landmarks and slam are made from the tables", "[tables]") {
    const std::string lm = help_of("landmarks");
    CHECK_THAT(lm, Catch::Contains(detector_list(true)));
    CHECK_THAT(lm, Catch::Contains(descriptor_list(true)));
    const std::string sl = help_of("slam");
    CHECK_THAT(sl, Catch::Contains(detector_list(true)));
    for (const auto& r : descriptor_table()) {
        // slam's descriptor check compares Hamming distances: its help lists the binary rows only
        const std::string entry = std::string(r.name) + (*r.help ? std::string(" (") + r.help + ")" : "");
        INFO(entry);
        const bool listed = sl.find(" " + entry + ",") != std::string::npos || sl.find(" " + entry + "\n") != std::string::npos ||
                            sl.find(" " + entry + " ") != std::string::npos;
        CHECK(listed == is_binary(r.id));
    }
}

TEST_CASE("the docs list the corner sources and the descriptors of the tables", "[tables]") {
    const std::string heading = "The corner sources and the descriptors: one table each";
    std::vector<std::string> want;
    for (const auto& r : detector_table()) want.push_back(r.name);
    CHECK(doc_list(heading, "corner source") == want);
    want.clear();
    for (const auto& r : descriptor_table()) want.push_back(r.name);
    CHECK(doc_list(heading, "descriptor") == want);
}
