// text_scan.hpp - small text tools for reading header lines: trimming, case
// folding, splitting into words, walking lines, and quoting excerpts of
// untrusted text safely inside error messages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace arbor::importers {

std::string_view trim(std::string_view s);
std::string lower(std::string_view s);
bool iequals(std::string_view a, std::string_view b);

// Whether the file name of `path` ends with `suffix`, ignoring case.
bool has_suffix(std::string_view path, std::string_view suffix);

// Words separated by spaces or tabs.
std::vector<std::string_view> split_words(std::string_view s);

// `s` in single quotes, cut to max_chars, with bytes that are not printable
// ASCII shown as '?', so binary garbage cannot garble a message.
std::string excerpt(std::string_view s, std::size_t max_chars = 60);

// Walks the lines of a text; a line ends at "\n" (a "\r" before it is dropped)
// or at the end of the text.
class LineCursor {
public:
    explicit LineCursor(std::string_view text) : text_(text) {}

    // The next line without its line break; false when the text is used up.
    bool next(std::string_view &line);
    // Bytes consumed so far, line breaks included.
    std::size_t offset() const { return pos_; }
    // 1-based number of the line `next` returned last.
    int number() const { return number_; }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    int number_ = 0;
};

} // namespace arbor::importers
