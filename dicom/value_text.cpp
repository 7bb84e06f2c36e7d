#include "value_text.hpp"

#include <cstdlib>

namespace arbor::dicom {

std::string display_date(const std::string &d)
{
    return d.size() == 8 ? d.substr(0, 4) + "-" + d.substr(4, 2) + "-" + d.substr(6, 2) : d;
}

std::string display_person_name(std::string s)
{
    for (char &c : s)
        if (c == '^')
            c = ' ';
    s.erase(s.find_last_not_of(' ') + 1);
    return s;
}

int count_value(const std::string &s)
{
    const std::size_t first = s.find_first_not_of(' ');
    if (first == std::string::npos || s.find_first_not_of("0123456789 ") != std::string::npos || s.size() > 9)
        return -1;
    return std::atoi(s.c_str() + first);
}

} // namespace arbor::dicom
