// format_table_test.cpp: the table of formats (format_fields() in harris_pkg.hpp) is the
// one list of fields: JSON, generics, cache-key text and names all follow it, including a
// field added to a copy of the table.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "model/harris/formats_json.hpp"
#include "model/harris/harris_pkg.hpp"

using namespace hc;

namespace {

/// Formats with one more field, as a new format field would be added.
struct FormatsPlus : Formats {
    int dummy_w = 7;
};

/// The real table, converted to FormatsPlus, plus a row for the new field.
std::array<FieldOf<FormatsPlus>, kFormatFields.size() + 1> plus_table() {
    std::array<FieldOf<FormatsPlus>, kFormatFields.size() + 1> t{};
    for (std::size_t k = 0; k < kFormatFields.size(); ++k) {
        const FormatField& f = kFormatFields[k];
        t[k] = {f.name, f.generic, f.vhdl_type, f.meaning, f.member};
    }
    t.back() = {"dummy_w", "DUMMY_W", "positive", "a field added for this test", &FormatsPlus::dummy_w};
    return t;
}

}  // namespace

TEST_CASE("every field of Formats has exactly one row in the table", "[model][formats]") {
    // a member left out of the table would make the struct larger than the table says
    STATIC_REQUIRE(sizeof(Formats) == kFormatFields.size() * sizeof(int));
    std::set<std::string> names, generics;
    std::vector<int Formats::*> members;   // member pointers have no order: count distinct ones by ==
    for (const auto& f : format_fields()) {
        names.insert(f.name);
        generics.insert(f.generic);
        if (std::find(members.begin(), members.end(), f.member) == members.end()) members.push_back(f.member);
        std::string upper = f.name;
        for (auto& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
        CHECK(upper == f.generic);   // naming convention: the generic is the field in capitals
        CHECK((std::string(f.vhdl_type) == "positive" || std::string(f.vhdl_type) == "natural"));
    }
    CHECK(names.size() == kFormatFields.size());
    CHECK(generics.size() == kFormatFields.size());
    CHECK(members.size() == kFormatFields.size());
}

TEST_CASE("the thesis formats write and read back as the JSON of the table, in table order", "[model][formats]") {
    const std::string text = formats_to_json(Formats{}, "thesis");
    CHECK(text ==
          "{\n  \"name\": \"thesis\",\n  \"sobel_w\": 11,\n  \"m_prod_w\": 21,\n  \"m_drop\": 5,\n  \"bf_sum_w\": 20,\n"
          "  \"bf_drop\": 4,\n  \"resp_w\": 32,\n  \"ktr_w\": 30,\n  \"k_shift1\": 5,\n  \"k_shift2\": 7,\n"
          "  \"thr_shift1\": 7,\n  \"thr_shift2\": 9\n}\n");
    CHECK(formats_from_json_text(text, "t") == Formats{});
    Formats f;
    f.m_drop = 6;
    f.thr_shift2 = 10;
    CHECK(formats_from_json_text(formats_to_json(f), "t") == f);
}

TEST_CASE("bad format JSON is bad input naming the key, the value and the known keys", "[model][formats]") {
    using Catch::Matchers::Contains;
    CHECK_THROWS_WITH(formats_from_json_text("{\"sobel_width\": 3}", "cfg.json"),
                      Contains("cfg.json: unknown key 'sobel_width' (format keys: sobel_w, m_prod_w, m_drop, bf_sum_w, "
                               "bf_drop, resp_w, ktr_w, k_shift1, k_shift2, thr_shift1, thr_shift2)"));
    CHECK_THROWS_WITH(formats_from_json_text("{\"m_drop\": 2.5}", "cfg.json"), Contains("cfg.json.m_drop: must be an integer"));
    CHECK_THROWS_WITH(formats_from_json_text("{\"m_drop\": 21}", "cfg.json"),
                      Contains("cfg.json: invalid formats: m_drop must be 0..m_prod_w-1"));
    CHECK_THROWS_AS(formats_from_json_text("{nope", "cfg.json"), InputError);
}

TEST_CASE("the generics are IMG_WIDTH, IMG_HEIGHT and one per row, named as the table names them", "[model][formats]") {
    const auto g = generics(Geometry{1241, 376}, Formats{});
    REQUIRE(g.size() == 2 + kFormatFields.size());
    CHECK(g[0] == std::pair<std::string, long>{"IMG_WIDTH", 1241});
    CHECK(g[1] == std::pair<std::string, long>{"IMG_HEIGHT", 376});
    CHECK(g[4] == std::pair<std::string, long>{"M_DROP", 5});
    CHECK(g.back() == std::pair<std::string, long>{"THR_SHIFT2", 9});
}

TEST_CASE("every field enters the formats hash: changing any one of them changes it", "[model][formats]") {
    const std::uint64_t base = formats_hash(Formats{});
    std::set<std::uint64_t> seen{base};
    for (const auto& fld : format_fields()) {
        Formats f;
        f.*(fld.member) += 1;
        INFO(fld.name);
        CHECK(formats_hash(f) != base);
        seen.insert(formats_hash(f));
    }
    CHECK(seen.size() == 1 + kFormatFields.size());
}

TEST_CASE("a field added to a copy of the table reaches JSON, generics, cache-key text and names", "[model][formats]") {
    const auto table = plus_table();
    FormatsPlus f;
    // JSON: written, read, and named in the error for an unknown key
    const auto j = fields_to_json(f, table);
    CHECK(j.at("dummy_w") == 7);
    FormatsPlus g;
    apply_fields(nlohmann::json::parse(R"({"dummy_w": 9, "m_drop": 6})"), g, table, "t");
    CHECK(g.dummy_w == 9);
    CHECK(g.m_drop == 6);
    CHECK_THROWS_WITH(apply_fields(nlohmann::json::parse(R"({"dumy_w": 9})"), g, table, "t"),
                      Catch::Matchers::EndsWith("thr_shift1, thr_shift2, dummy_w)"));
    // generics handed to GHDL and Verilator
    const auto gen = generics_of(Geometry{}, f, table);
    REQUIRE(gen.size() == 2 + table.size());
    CHECK(gen.back() == std::pair<std::string, long>{"DUMMY_W", 7});
    // the cache key's text: two configurations that differ only in the new field differ
    CHECK(fields_text(f, table).ends_with(",dummy_w=7"));
    CHECK(fields_text(f, table) != fields_text(g, table));
    FormatsPlus h;
    h.dummy_w = 8;
    CHECK(fields_text(h, table) != fields_text(f, table));
    // names of sweep points
    CHECK(describe_difference_of(h, table) == "dummy_w=8");
    CHECK(describe_difference_of(f, table) == "thesis");
    CHECK(table.back().default_value() == 7);
}
