// json_stream.hpp - JSON written as it is produced: trees and branch lists of
// noisy scans have millions of entries, too many to build as one document
// in memory first.  Numbers are written exactly (integers without a
// fraction, others with 17 significant digits); NaN and infinity as null.
#pragma once

#include "core/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace arbor::io {

class JsonStream {
public:
    explicit JsonStream(AtomicFile &out) : out_(out) {}
    void raw(const std::string &s) { out_.write(s); }
    void number(double x)
    {
        if (!std::isfinite(x)) {
            raw("null");
            return;
        }
        char buf[40];
        if (x == std::floor(x) && std::fabs(x) < 1e15)
            std::snprintf(buf, sizeof buf, "%.0f", x);
        else
            std::snprintf(buf, sizeof buf, "%.17g", x);
        raw(buf);
    }
    void string(const std::string &s) { raw(nlohmann::json(s).dump()); }
    void key(const char *k)
    {
        string(k);
        raw(":");
    }
    void triple(const std::array<double, 3> &p)
    {
        raw("[");
        for (int i = 0; i < 3; ++i) {
            if (i)
                raw(",");
            number(p[i]);
        }
        raw("]");
    }

private:
    AtomicFile &out_;
};

} // namespace arbor::io
