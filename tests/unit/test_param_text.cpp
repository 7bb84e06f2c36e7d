// Parameter values as command-line text, checked against descriptions.
#include "host/descriptor_rules.hpp"
#include "host/param_text.hpp"

#include <gtest/gtest.h>

namespace arbor {
namespace {

arbor_param_desc desc(arbor_param_type type, uint32_t components, double lo, double hi)
{
    arbor_param_desc d{};
    d.struct_size = sizeof(d);
    d.type = type;
    d.id = "dims";
    d.name = "Dims";
    d.group = d.unit = d.hint = "";
    d.components = components;
    d.min_value = lo;
    d.max_value = hi;
    d.default_text = "";
    return d;
}

TEST(ParamText, ParsesVectorsInEveryCommonSpelling)
{
    const arbor_param_desc d = desc(ARBOR_PARAM_INT, 3, 1, 1e9);
    for (const char *text : {"64,32,16", "64 32 16", "64x32x16"}) {
        const ParamText t = parse_param_value(d, text);
        EXPECT_EQ(t.value.number[0], 64);
        EXPECT_EQ(t.value.number[1], 32);
        EXPECT_EQ(t.value.number[2], 16);
        EXPECT_EQ(format_param_value(d, t.value), "64,32,16");
    }
}

TEST(ParamText, RefusesValuesOutsideTheDescription)
{
    const arbor_param_desc d = desc(ARBOR_PARAM_INT, 3, 1, 1e9);
    EXPECT_THROW(parse_param_value(d, "64,32"), std::invalid_argument);
    EXPECT_THROW(parse_param_value(d, "0,32,16"), std::invalid_argument);
    EXPECT_THROW(parse_param_value(d, "1.5,2,3"), std::invalid_argument);
    EXPECT_THROW(parse_param_value(d, "a,b,c"), std::invalid_argument);
    const arbor_param_desc f = desc(ARBOR_PARAM_FLOAT, 1, 0, 300);
    EXPECT_EQ(parse_param_value(f, "12.5").value.number[0], 12.5);
    EXPECT_THROW(parse_param_value(f, "nan"), std::invalid_argument);
    EXPECT_THROW(parse_param_value(f, "1e999"), std::invalid_argument);
    EXPECT_THROW(parse_param_value(f, "301"), std::invalid_argument);
}

TEST(ParamText, ChoicesBooleansAndText)
{
    const char *choices[] = {"little", "big"};
    arbor_param_desc c = desc(ARBOR_PARAM_CHOICE, 1, 0, 1);
    c.choice_count = 2;
    c.choices = choices;
    EXPECT_EQ(parse_param_value(c, "big").value.number[0], 1);
    try {
        parse_param_value(c, "middle");
        FAIL();
    } catch (const std::invalid_argument &e) {
        EXPECT_NE(std::string(e.what()).find("one of: little, big"), std::string::npos);
    }
    const arbor_param_desc b = desc(ARBOR_PARAM_BOOL, 1, 0, 1);
    EXPECT_EQ(parse_param_value(b, "yes").value.number[0], 1);
    EXPECT_EQ(parse_param_value(b, "off").value.number[0], 0);
    EXPECT_THROW(parse_param_value(b, "maybe"), std::invalid_argument);
    const arbor_param_desc s = desc(ARBOR_PARAM_STRING, 1, 0, 0);
    const ParamText t = parse_param_value(s, "1.2.840.113619");
    EXPECT_STREQ(t.value.text, "1.2.840.113619");
}

TEST(DescriptorRules, PluginIds)
{
    EXPECT_EQ(check_plugin_id("org.arbor.importer.nrrd"), "");
    EXPECT_EQ(check_plugin_id("com.example.filter-x.v2"), "");
    EXPECT_NE(check_plugin_id("Org.Arbor.Thing"), "");
    EXPECT_NE(check_plugin_id("arbor.nrrd"), "");
    EXPECT_NE(check_plugin_id("org..arbor.x"), "");
    EXPECT_NE(check_plugin_id(nullptr), "");
    EXPECT_EQ(check_semver("1.0.0"), "");
    EXPECT_EQ(check_semver("2.10.3-beta.1"), "");
    EXPECT_NE(check_semver("1.0"), "");
    EXPECT_NE(check_semver("01.0.0"), "");
}

TEST(DescriptorRules, ParameterDescriptions)
{
    arbor_param_desc d = desc(ARBOR_PARAM_FLOAT, 1, 0, 300);
    d.id = "flow-rate";
    d.default_value[0] = 50;
    EXPECT_EQ(check_param_desc(&d), "");
    d.default_value[0] = 400;
    EXPECT_NE(check_param_desc(&d).find("outside its range"), std::string::npos);
    d.default_value[0] = 50;
    d.id = "Flow_Rate";
    EXPECT_NE(check_param_desc(&d), "");
    d.id = "flow-rate";
    d.components = 5;
    EXPECT_NE(check_param_desc(&d), "");
    d.components = 1;
    d.flags = ARBOR_PARAM_FLAG_LOG_SCALE;
    EXPECT_NE(check_param_desc(&d).find("log-scale"), std::string::npos);
    arbor_param_desc c = desc(ARBOR_PARAM_CHOICE, 1, 0, 1);
    const char *dup[] = {"ramp", "ramp"};
    c.choice_count = 2;
    c.choices = dup;
    EXPECT_NE(check_param_desc(&c).find("twice"), std::string::npos);
}

} // namespace
} // namespace arbor
