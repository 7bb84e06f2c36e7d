// The scoped JSON writer: separators and nesting, the number rules
// (integers below 2^53 exact, other doubles round-trip, non-finite as null),
// strings that always come out as valid UTF-8, both layouts, and files that
// are replaced only by complete documents.
#include "io/json_writer.hpp"

#include "test_paths.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <stdexcept>
#include <vector>

using namespace arbor;
using io::JsonLayout;
using io::JsonWriter;

namespace {

std::string one_value(double x)
{
    std::string s;
    JsonWriter j(s);
    j.value(x);
    j.finish();
    return s;
}

std::string one_string(std::string_view text)
{
    std::string s;
    JsonWriter j(s);
    j.value(text);
    j.finish();
    return s;
}

std::string read(const std::filesystem::path &p)
{
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

} // namespace

TEST(JsonWriter, ScopesPlaceEverySeparator)
{
    std::string s;
    JsonWriter j(s);
    {
        auto doc = j.object();
        j.field("format", "x/1");
        j.field("dims", std::vector<int>{3, 4, 5});
        {
            auto empty = j.object("empty");
        }
        {
            auto none = j.array("none");
        }
        auto rows = j.array("rows");
        for (int r = 0; r < 2; ++r) {
            auto row = j.object();
            j.field("id", r);
            j.field("ok", r == 1);
            j.key("nothing");
            j.null();
        }
    }
    j.finish();
    EXPECT_EQ(s, R"({"format":"x/1","dims":[3,4,5],"empty":{},"none":[],)"
                 R"("rows":[{"id":0,"ok":false,"nothing":null},{"id":1,"ok":true,"nothing":null}]})");
}

TEST(JsonWriter, ColumnsWriteOneArrayPerCall)
{
    std::string s;
    JsonWriter j(s);
    {
        auto doc = j.object();
        const double v[] = {0.5, 2.0, -1.0};
        j.column("half", 3, [&](std::size_t i) { return v[i]; });
        j.column("kind", 2, [](std::size_t i) { return static_cast<uint8_t>(i + 1); });
    }
    j.finish();
    EXPECT_EQ(s, R"({"half":[0.5,2,-1],"kind":[1,2]})");
}

TEST(JsonWriter, IntegralDoublesBelowTwoTo53AreIntegers)
{
    EXPECT_EQ(one_value(0.0), "0");
    EXPECT_EQ(one_value(-0.0), "0");
    EXPECT_EQ(one_value(3.0), "3");
    EXPECT_EQ(one_value(-17.0), "-17");
    EXPECT_EQ(one_value(1e15), "1000000000000000");
    EXPECT_EQ(one_value(9007199254740991.0), "9007199254740991");
    EXPECT_EQ(one_value(-9007199254740991.0), "-9007199254740991");
    // From 2^53 on a double no longer counts every integer: written as a double.
    const std::string big = one_value(9007199254740992.0);
    EXPECT_NE(big.find_first_of(".e"), std::string::npos) << big;
    EXPECT_EQ(std::strtod(big.c_str(), nullptr), 9007199254740992.0);
}

TEST(JsonWriter, OtherDoublesReadBackExactly)
{
    EXPECT_EQ(one_value(0.1), "0.1");
    EXPECT_EQ(one_value(-2.5), "-2.5");
    EXPECT_EQ(one_value(1e-7), "1e-7");
    std::mt19937_64 random(7);
    std::uniform_int_distribution<uint64_t> bits;
    int checked = 0;
    while (checked < 20000) {
        const uint64_t b = bits(random);
        double x;
        std::memcpy(&x, &b, sizeof x);
        if (!std::isfinite(x))
            continue;
        const std::string text = one_value(x);
        ASSERT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
        ++checked;
    }
    for (double x : {1.0 / 3.0, 2.0 / 3.0, 1e300, 5e-324, std::numeric_limits<double>::max(),
                     std::numeric_limits<double>::min(), 0.30000000000000004, 123456.789}) {
        const std::string text = one_value(x);
        EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
        EXPECT_LE(text.size(), 24u) << text;
    }
}

TEST(JsonWriter, NonFiniteNumbersAreNull)
{
    EXPECT_EQ(one_value(std::numeric_limits<double>::quiet_NaN()), "null");
    EXPECT_EQ(one_value(std::numeric_limits<double>::infinity()), "null");
    EXPECT_EQ(one_value(-std::numeric_limits<double>::infinity()), "null");
}

TEST(JsonWriter, IntegersOfEveryWidth)
{
    std::string s;
    JsonWriter j(s);
    {
        auto a = j.array();
        j.value(int8_t{-8});
        j.value(uint16_t{65535});
        j.value(int32_t{-1});
        j.value(uint32_t{4294967295u});
        j.value(std::numeric_limits<int64_t>::min());
        j.value(std::numeric_limits<uint64_t>::max());
        j.value(std::size_t{12});
    }
    j.finish();
    EXPECT_EQ(s, "[-8,65535,-1,4294967295,-9223372036854775808,18446744073709551615,12]");
}

TEST(JsonWriter, StringsAreEscaped)
{
    EXPECT_EQ(one_string("a\"b\\c"), R"("a\"b\\c")");
    EXPECT_EQ(one_string("line\nnext\ttab"), R"("line\nnext\ttab")");
    EXPECT_EQ(one_string(std::string_view("nul\0x", 5)), R"("nul\u0000x")");
    EXPECT_EQ(one_string("\x01"), R"("\u0001")");
    EXPECT_EQ(one_string("a/b"), R"("a/b")");
}

TEST(JsonWriter, ValidUtf8PassesUnchanged)
{
    EXPECT_EQ(one_string("Sch\xc3\xa4" "del"), "\"Sch\xc3\xa4" "del\"");        // ä
    EXPECT_EQ(one_string("\xe2\x82\xac"), "\"\xe2\x82\xac\"");                    // €
    EXPECT_EQ(one_string("\xf0\x9f\xa7\xa0"), "\"\xf0\x9f\xa7\xa0\"");            // U+1F9E0
    EXPECT_EQ(one_string("\xef\xbf\xbd"), "\"\xef\xbf\xbd\"");                    // U+FFFD itself
}

TEST(JsonWriter, InvalidBytesBecomeReplacementCharacters)
{
    const std::string r = "\xef\xbf\xbd"; // U+FFFD
    EXPECT_EQ(one_string("M\xfcller"), "\"M" + r + "ller\"");                 // Latin-1 ü
    EXPECT_EQ(one_string("end\xc3"), "\"end" + r + "\"");                      // truncated at the end
    EXPECT_EQ(one_string("\xc3" "A"), "\"" + r + "A\"");                       // truncated, then ASCII
    EXPECT_EQ(one_string("\xe2\x82"), "\"" + r + r + "\"");                    // truncated 3-byte
    EXPECT_EQ(one_string("\xc0\xaf"), "\"" + r + r + "\"");                    // overlong '/'
    EXPECT_EQ(one_string("\xed\xa0\x80"), "\"" + r + r + r + "\"");            // a surrogate
    EXPECT_EQ(one_string("\xf4\x90\x80\x80"), "\"" + r + r + r + r + "\"");    // beyond U+10FFFF
    EXPECT_EQ(one_string("\x80\xbf"), "\"" + r + r + "\"");                    // stray continuations
    EXPECT_EQ(one_string("\xff"), "\"" + r + "\"");
}

TEST(JsonWriter, KeysAreRepairedToo)
{
    std::string s;
    JsonWriter j(s);
    {
        auto o = j.object();
        j.field("id\xe9", 1);
    }
    j.finish();
    EXPECT_EQ(s, "{\"id\xef\xbf\xbd\":1}");
}

TEST(JsonWriter, IndentedLayoutPutsMembersOnLinesAndArraysOnOne)
{
    std::string s;
    JsonWriter j(s, JsonLayout::indented);
    {
        auto doc = j.object();
        j.field("a", std::vector<double>{1, 2.5});
        auto b = j.object("b");
        j.field("c", "d");
    }
    j.finish();
    EXPECT_EQ(s, "{\n  \"a\": [1, 2.5],\n  \"b\": {\n    \"c\": \"d\"\n  }\n}");
}

TEST(JsonWriter, FinishRefusesAnIncompleteDocument)
{
    std::string s;
    JsonWriter j(s);
    EXPECT_THROW(j.finish(), std::logic_error); // nothing written
    auto doc = j.object();
    j.field("x", 1);
    EXPECT_THROW(j.finish(), std::logic_error); // still open
}

TEST(JsonWriter, LargeOutputIsTheSameInAFileAndAString)
{
    const std::filesystem::path dir = test::scratch_dir();
    const auto write = [](JsonWriter &j) {
        auto doc = j.object();
        j.column("x", 300000, [](std::size_t i) { return static_cast<double>(i) * 0.37; });
        j.column("i", 300000, [](std::size_t i) { return static_cast<uint32_t>(i * 7919u); });
    };
    std::string text;
    {
        JsonWriter j(text);
        write(j);
        j.finish();
    }
    EXPECT_GT(text.size(), std::size_t{4} << 20); // well beyond one buffer
    AtomicFile file(dir / "large.json");
    JsonWriter j(file);
    write(j);
    j.finish();
    file.commit();
    EXPECT_EQ(read(dir / "large.json"), text);
}

TEST(JsonWriter, FilesAreReplacedOnlyByCompleteDocuments)
{
    const std::filesystem::path p = test::scratch_dir() / "doc.json";
    io::write_json_file(p, JsonLayout::compact, [](JsonWriter &j) { j.field("n", 1); });
    EXPECT_EQ(read(p), "{\"n\":1}\n");
    EXPECT_THROW(io::write_json_file(p, JsonLayout::compact,
                                     [](JsonWriter &j) {
                                         auto a = j.array("partial");
                                         j.value(2);
                                         throw std::runtime_error("stopped half way");
                                     }),
                 std::runtime_error);
    EXPECT_EQ(read(p), "{\"n\":1}\n");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(p.parent_path()),
                            std::filesystem::directory_iterator()),
              1); // no temporary file left behind
}
