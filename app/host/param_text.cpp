#include "param_text.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <charconv>
#include <vector>

namespace arbor {

namespace {

// The shortest text that reads back as exactly x, so a value survives a
// session file or a document copy bit for bit.
std::string number_text(double x)
{
    char buf[40];
    const auto r = std::to_chars(buf, buf + sizeof buf, x);
    return std::string(buf, r.ptr);
}

std::vector<std::string> split_components(const std::string &text)
{
    // Accept "1,2,3", "1 2 3" and "1x2x3" (the way people write dims).
    std::vector<std::string> parts;
    std::string cur;
    for (char c : text) {
        if (c == ',' || c == ' ' || c == 'x' || c == 'X') {
            if (!cur.empty())
                parts.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    if (!cur.empty())
        parts.push_back(cur);
    return parts;
}

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

} // namespace

ParamText parse_param_value(const arbor_param_desc &d, const std::string &text)
{
    const std::string who = "parameter '" + std::string(d.id) + "'";
    ParamText out;
    out.value.struct_size = sizeof(arbor_param_value);
    out.value.type = d.type;
    out.value.components = d.components;
    switch (d.type) {
    case ARBOR_PARAM_STRING:
    case ARBOR_PARAM_PATH:
        out.storage = text;
        out.value.text = out.storage.c_str();
        return out;
    case ARBOR_PARAM_BOOL: {
        const std::string t = lower(text);
        if (t == "1" || t == "true" || t == "yes" || t == "on")
            out.value.number[0] = 1;
        else if (t == "0" || t == "false" || t == "no" || t == "off")
            out.value.number[0] = 0;
        else
            throw std::invalid_argument(who + ": '" + text + "' is not true or false");
        return out;
    }
    case ARBOR_PARAM_CHOICE:
        for (uint32_t c = 0; c < d.choice_count; ++c)
            if (text == d.choices[c]) {
                out.value.number[0] = c;
                return out;
            }
        throw std::invalid_argument(who + ": '" + text + "' is not " + describe_param_domain(d));
    case ARBOR_PARAM_FLOAT:
    case ARBOR_PARAM_INT: {
        const auto parts = split_components(text);
        if (parts.size() != d.components)
            throw std::invalid_argument(who + ": expects " + std::to_string(d.components) +
                                        (d.components == 1 ? " number" : " numbers separated by commas") +
                                        ", got '" + text + "'");
        for (std::size_t c = 0; c < parts.size(); ++c) {
            char *end = nullptr;
            errno = 0;
            const double v = std::strtod(parts[c].c_str(), &end);
            if (!end || *end != '\0' || errno == ERANGE || !std::isfinite(v))
                throw std::invalid_argument(who + ": '" + parts[c] + "' is not a number");
            if (d.type == ARBOR_PARAM_INT && v != std::floor(v))
                throw std::invalid_argument(who + ": '" + parts[c] + "' is not a whole number");
            if (v < d.min_value || v > d.max_value)
                throw std::invalid_argument(who + ": " + parts[c] + " lies outside " +
                                            describe_param_domain(d));
            out.value.number[c] = v;
        }
        return out;
    }
    default:
        throw std::invalid_argument(who + ": unknown parameter type");
    }
}

std::string format_param_value(const arbor_param_desc &d, const arbor_param_value &v)
{
    switch (d.type) {
    case ARBOR_PARAM_STRING:
    case ARBOR_PARAM_PATH: return v.text ? v.text : "";
    case ARBOR_PARAM_BOOL: return v.number[0] != 0 ? "true" : "false";
    case ARBOR_PARAM_CHOICE: {
        const auto i = static_cast<uint32_t>(v.number[0]);
        return i < d.choice_count ? d.choices[i] : "?";
    }
    default: {
        std::string s;
        for (uint32_t c = 0; c < d.components; ++c)
            s += (c ? "," : "") + number_text(v.number[c]);
        return s;
    }
    }
}

std::string describe_param_domain(const arbor_param_desc &d)
{
    switch (d.type) {
    case ARBOR_PARAM_STRING: return "text";
    case ARBOR_PARAM_PATH: return "a file path";
    case ARBOR_PARAM_BOOL: return "true or false";
    case ARBOR_PARAM_CHOICE: {
        std::string s = "one of: ";
        for (uint32_t c = 0; c < d.choice_count; ++c)
            s += (c ? ", " : "") + std::string(d.choices[c]);
        return s;
    }
    default:
        return "[" + number_text(d.min_value) + ", " + number_text(d.max_value) + "]";
    }
}

std::string format_param_default(const arbor_param_desc &d)
{
    arbor_param_value v{};
    v.type = d.type;
    v.components = d.components;
    for (int c = 0; c < ARBOR_PARAM_MAX_COMPONENTS; ++c)
        v.number[c] = d.default_value[c];
    v.text = d.default_text;
    return format_param_value(d, v);
}

} // namespace arbor
