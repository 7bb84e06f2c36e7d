// arbor/sdk/params.hpp - describe parameters in C++ and store their values
// behind the arbor.params/1 interface.  Part of the optional C++ layer.
//
//     ParamSpec::real("sigma", "Sigma", 1.0, 0.1, 10.0).unit("mm").hint("...")
//
// A ParamSet owns the specs (and the strings the C descriptions point into),
// validates every value against its description and keeps the current values.
#pragma once

#include <arbor/params.h>

#include "error.hpp"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace arbor::sdk {

class ParamSpec {
public:
    static ParamSpec real(std::string id, std::string name, double def, double min, double max)
    {
        return numeric(ARBOR_PARAM_FLOAT, std::move(id), std::move(name), {def}, min, max);
    }
    static ParamSpec integer(std::string id, std::string name, double def, double min, double max)
    {
        return numeric(ARBOR_PARAM_INT, std::move(id), std::move(name), {def}, min, max);
    }
    // FLOAT or INT with 2..4 components.
    static ParamSpec vector(arbor_param_type type, std::string id, std::string name,
                            std::vector<double> defs, double min, double max)
    {
        return numeric(type, std::move(id), std::move(name), std::move(defs), min, max);
    }
    static ParamSpec boolean(std::string id, std::string name, bool def)
    {
        return numeric(ARBOR_PARAM_BOOL, std::move(id), std::move(name), {def ? 1.0 : 0.0}, 0, 1);
    }
    static ParamSpec choice(std::string id, std::string name, std::vector<std::string> ids,
                            std::size_t def, std::vector<std::string> labels = {})
    {
        ParamSpec s = numeric(ARBOR_PARAM_CHOICE, std::move(id), std::move(name),
                              {static_cast<double>(def)}, 0, static_cast<double>(ids.size()) - 1);
        s.choices_ = std::move(ids);
        s.choice_names_ = std::move(labels);
        return s;
    }
    static ParamSpec text(std::string id, std::string name, std::string def)
    {
        ParamSpec s = numeric(ARBOR_PARAM_STRING, std::move(id), std::move(name), {0}, 0, 0);
        s.default_text_ = std::move(def);
        return s;
    }
    static ParamSpec path(std::string id, std::string name, std::string def = "")
    {
        ParamSpec s = text(std::move(id), std::move(name), std::move(def));
        s.desc_.type = ARBOR_PARAM_PATH;
        return s;
    }

    ParamSpec &unit(std::string u) { unit_ = std::move(u); return *this; }
    ParamSpec &group(std::string g) { group_ = std::move(g); return *this; }
    ParamSpec &hint(std::string h) { hint_ = std::move(h); return *this; }
    ParamSpec &flags(arbor_param_flags f) { desc_.flags |= f; return *this; }

    const std::string &id() const { return id_; }
    const std::vector<std::string> &choices() const { return choices_; }
    const std::string &default_text() const { return default_text_; }

    // The C description; pointers refer into this object, which must not move
    // afterwards (ParamSet guarantees that).
    const arbor_param_desc &describe()
    {
        desc_.id = id_.c_str();
        desc_.name = name_.c_str();
        desc_.group = group_.c_str();
        desc_.unit = unit_.c_str();
        desc_.hint = hint_.c_str();
        desc_.default_text = default_text_.c_str();
        choice_ptrs_.clear();
        for (const auto &c : choices_)
            choice_ptrs_.push_back(c.c_str());
        choice_name_ptrs_.clear();
        for (const auto &c : choice_names_)
            choice_name_ptrs_.push_back(c.c_str());
        desc_.choice_count = static_cast<uint32_t>(choices_.size());
        desc_.choices = choices_.empty() ? nullptr : choice_ptrs_.data();
        desc_.choice_names =
            choice_names_.size() == choices_.size() && !choices_.empty() ? choice_name_ptrs_.data()
                                                                         : nullptr;
        return desc_;
    }
    const arbor_param_desc &description() const { return desc_; }

private:
    static ParamSpec numeric(arbor_param_type type, std::string id, std::string name,
                             std::vector<double> defs, double min, double max)
    {
        ParamSpec s;
        s.id_ = std::move(id);
        s.name_ = std::move(name);
        s.desc_.struct_size = sizeof(arbor_param_desc);
        s.desc_.type = type;
        s.desc_.components = static_cast<uint32_t>(defs.size());
        s.desc_.min_value = min;
        s.desc_.max_value = max;
        for (std::size_t i = 0; i < defs.size() && i < ARBOR_PARAM_MAX_COMPONENTS; ++i)
            s.desc_.default_value[i] = defs[i];
        return s;
    }

    arbor_param_desc desc_{};
    std::string id_, name_, group_, unit_, hint_, default_text_;
    std::vector<std::string> choices_, choice_names_;
    std::vector<const char *> choice_ptrs_, choice_name_ptrs_;
};

class ParamSet {
public:
    explicit ParamSet(std::vector<ParamSpec> specs) : specs_(std::move(specs))
    {
        values_.resize(specs_.size());
        for (std::size_t i = 0; i < specs_.size(); ++i) {
            const arbor_param_desc &d = specs_[i].describe();
            for (int c = 0; c < ARBOR_PARAM_MAX_COMPONENTS; ++c)
                values_[i].number[c] = d.default_value[c];
            values_[i].text = specs_[i].default_text();
        }
    }
    ParamSet(const ParamSet &) = delete;
    ParamSet &operator=(const ParamSet &) = delete;

    uint32_t count() const { return static_cast<uint32_t>(specs_.size()); }
    const arbor_param_desc *describe(uint32_t index) const
    {
        return index < specs_.size() ? &specs_[index].description() : nullptr;
    }

    void get(std::string_view id, arbor_param_value &out) const
    {
        const std::size_t i = index_of(id);
        const arbor_param_desc &d = specs_[i].description();
        out.type = d.type;
        out.components = d.components;
        for (int c = 0; c < ARBOR_PARAM_MAX_COMPONENTS; ++c)
            out.number[c] = values_[i].number[c];
        out.text = values_[i].text.c_str();
    }

    void set(std::string_view id, const arbor_param_value &v)
    {
        const std::size_t i = index_of(id);
        const arbor_param_desc &d = specs_[i].description();
        const std::string name = "parameter '" + specs_[i].id() + "'";
        if (v.type != d.type)
            fail(ARBOR_ERROR_INVALID_ARGUMENT, name + ": value of the wrong type");
        if (v.components != d.components)
            fail(ARBOR_ERROR_INVALID_ARGUMENT,
                 name + ": expects " + std::to_string(d.components) + " component(s), got " +
                     std::to_string(v.components));
        if (d.type == ARBOR_PARAM_STRING || d.type == ARBOR_PARAM_PATH) {
            if (!v.text)
                fail(ARBOR_ERROR_INVALID_ARGUMENT, name + ": text is NULL");
            values_[i].text = v.text;
            values_[i].set = true;
            return;
        }
        for (uint32_t c = 0; c < d.components; ++c) {
            const double x = v.number[c];
            if (!std::isfinite(x))
                fail(ARBOR_ERROR_OUT_OF_RANGE, name + ": value is not a finite number");
            if (d.type != ARBOR_PARAM_FLOAT && x != std::floor(x))
                fail(ARBOR_ERROR_OUT_OF_RANGE, name + ": " + format(x) + " is not a whole number");
            if (x < d.min_value || x > d.max_value) {
                if (d.type == ARBOR_PARAM_CHOICE)
                    fail(ARBOR_ERROR_OUT_OF_RANGE,
                         name + ": choice index " + format(x) + " out of range");
                fail(ARBOR_ERROR_OUT_OF_RANGE, name + ": " + format(x) + " outside [" +
                                                   format(d.min_value) + ", " +
                                                   format(d.max_value) + "]");
            }
        }
        for (uint32_t c = 0; c < d.components; ++c)
            values_[i].number[c] = v.number[c];
        values_[i].set = true;
    }

    // Typed access for plugin code.
    double number(std::string_view id, int component = 0) const
    {
        return values_[index_of(id)].number[component];
    }
    int64_t integer(std::string_view id, int component = 0) const
    {
        return static_cast<int64_t>(number(id, component));
    }
    bool flag(std::string_view id) const { return number(id) != 0.0; }
    const std::string &choice(std::string_view id) const
    {
        const std::size_t i = index_of(id);
        return specs_[i].choices()[static_cast<std::size_t>(values_[i].number[0])];
    }
    const std::string &text(std::string_view id) const { return values_[index_of(id)].text; }
    // Whether the host set the parameter explicitly (for REQUIRED ones).
    bool was_set(std::string_view id) const { return values_[index_of(id)].set; }

    // Throws ARBOR_ERROR_INVALID_ARGUMENT naming the first REQUIRED parameter
    // that was never set; `what` says what needs it ("headerless raw file").
    void require_all(const std::string &what) const
    {
        for (std::size_t i = 0; i < specs_.size(); ++i)
            if ((specs_[i].description().flags & ARBOR_PARAM_FLAG_REQUIRED) && !values_[i].set)
                fail(ARBOR_ERROR_INVALID_ARGUMENT,
                     what + " needs parameter '" + specs_[i].id() + "' (" +
                         specs_[i].description().hint + ")");
    }

private:
    struct Value {
        double number[ARBOR_PARAM_MAX_COMPONENTS] = {};
        std::string text;
        bool set = false;
    };

    std::size_t index_of(std::string_view id) const
    {
        for (std::size_t i = 0; i < specs_.size(); ++i)
            if (specs_[i].id() == id)
                return i;
        fail(ARBOR_ERROR_NOT_FOUND, "no parameter '" + std::string(id) + "'");
    }

    static std::string format(double x)
    {
        std::string s = std::to_string(x);
        if (s.find('.') != std::string::npos) {
            while (!s.empty() && s.back() == '0')
                s.pop_back();
            if (!s.empty() && s.back() == '.')
                s.pop_back();
        }
        return s;
    }

    std::vector<ParamSpec> specs_;
    std::vector<Value> values_;
};

} // namespace arbor::sdk
