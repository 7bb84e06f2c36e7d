// json_writer.hpp - JSON written as it is produced, on RapidJSON's streaming
// writers: the trees and branch lists of noisy scans have millions of
// entries, too many to build as one document in memory first.  Objects and
// arrays are scopes that close themselves, and members are written as
// key-value pairs, so commas, braces and keys cannot be written wrongly.
//
// Numbers: integral values of magnitude below 2^53 as integers, others as
// the short text RapidJSON's Grisu2 gives, which reads back as the same
// double; NaN and infinities as null.  Strings (values and keys) always come
// out as valid UTF-8: bytes that are not part of a valid UTF-8 sequence (a
// file name in another character set) become U+FFFD.
//
//     io::write_json_file(path, io::JsonLayout::indented, [&](io::JsonWriter &j) {
//         j.field("format", "arbor-example/1");
//         {
//             auto volume = j.object("volume");
//             j.field("source", source);
//             j.field("dims", geometry.dims); // any range: an array
//         }
//         auto kept = j.array("kept");
//         for (uint32_t b : branches)
//             j.value(b);
//     });
#pragma once

#include "core/atomic_file.hpp"

#include <concepts>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <ranges>
#include <string>
#include <string_view>

namespace arbor::io {

enum class JsonLayout {
    compact,  // no whitespace at all: files for programs
    indented, // a member per line, arrays on one line: files people read
};

class JsonWriter {
public:
    // Writes into `file` (the caller commits it after finish()) or appends
    // to `text`.  Output is buffered and handed on in large blocks.
    explicit JsonWriter(AtomicFile &file, JsonLayout layout = JsonLayout::compact);
    explicit JsonWriter(std::string &text, JsonLayout layout = JsonLayout::compact);
    ~JsonWriter();
    JsonWriter(const JsonWriter &) = delete;
    JsonWriter &operator=(const JsonWriter &) = delete;

    // An open object or array; closes it when it goes out of scope.  While
    // an exception unwinds it writes nothing (that output is abandoned).
    class [[nodiscard]] Scope {
    public:
        Scope(Scope &&other) noexcept;
        Scope(const Scope &) = delete;
        Scope &operator=(const Scope &) = delete;
        Scope &operator=(Scope &&) = delete;
        ~Scope();

    private:
        friend class JsonWriter;
        Scope(JsonWriter &writer, bool array);
        JsonWriter *writer_;
        bool array_;
        int exceptions_; // std::uncaught_exceptions() when opened
    };

    // As a value: the document itself, or an element of an array.
    Scope object();
    Scope array();
    // As a member of the enclosing object.
    Scope object(std::string_view key);
    Scope array(std::string_view key);

    // The key of the next member; prefer field(), object(key), array(key).
    void key(std::string_view key);

    void value(double x);
    void value(std::string_view text);
    void value(const char *text) { value(std::string_view(text)); }
    void value(const std::string &text) { value(std::string_view(text)); }
    void value(bool b);
    template <std::integral T>
        requires(!std::same_as<T, bool>)
    void value(T x)
    {
        if constexpr (std::is_signed_v<T>)
            signed_value(x);
        else
            unsigned_value(x);
    }
    void null();

    // An array of every element of `range`.
    template <std::ranges::input_range R> void values(const R &range)
    {
        const Scope a = array();
        for (const auto &x : range)
            value(x);
    }
    // An array of at(0) .. at(count - 1): a column of a table.
    template <class At> void column(std::string_view key, std::size_t count, At &&at)
    {
        const Scope a = array(key);
        for (std::size_t i = 0; i < count; ++i)
            value(at(i));
    }

    // key: value; a range (other than a string) becomes an array.
    template <class T> void field(std::string_view k, const T &v)
    {
        key(k);
        if constexpr (std::is_convertible_v<const T &, std::string_view>)
            value(std::string_view(v));
        else if constexpr (std::ranges::input_range<T>)
            values(v);
        else
            value(v);
    }

    // The document is complete: hands on what is buffered.  Throws
    // std::logic_error when it is not (an object or array still open, or
    // nothing written).
    void finish();

private:
    struct Rapid;
    void signed_value(int64_t x);
    void unsigned_value(uint64_t x);
    void end(bool array);
    void drain();

    AtomicFile *file_ = nullptr;
    std::string *text_ = nullptr;
    std::unique_ptr<Rapid> rapid_;
};

// A whole file holding one object: opens it, lets `members` write into it,
// closes it, ends the file with a newline and commits it (so an existing
// file is replaced only by a complete one).
void write_json_file(const std::filesystem::path &path, JsonLayout layout,
                     const std::function<void(JsonWriter &)> &members);

} // namespace arbor::io
