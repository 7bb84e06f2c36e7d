#include "json_writer.hpp"

#include <rapidjson/encodings.h>
#include <rapidjson/prettywriter.h>
#include <rapidjson/stringbuffer.h>
#include <rapidjson/writer.h>

#include <cmath>
#include <exception>
#include <optional>
#include <stdexcept>

namespace arbor::io {

namespace {

// What the writer holds before handing it on to the file or string.
constexpr std::size_t kDrainBytes = std::size_t{1} << 18;

// Integers up to here are exact in a double and written without a fraction.
constexpr double kExactIntegers = 9007199254740992.0; // 2^53

// RapidJSON's UTF-8 decoder reads through this: past the end it sees NUL,
// which no multi-byte sequence accepts, so a truncated sequence fails there
// instead of reading beyond the text.
struct BoundedText {
    using Ch = char;
    const char *at;
    const char *end;
    Ch Peek() const { return at < end ? *at : '\0'; }
    Ch Take() { return at < end ? *at++ : '\0'; }
    std::size_t Tell() const { return 0; }
};

// `text` itself when it is valid UTF-8; otherwise a copy in `repaired` with
// every byte that does not belong to a valid sequence (stray continuation
// bytes, truncated or overlong sequences, surrogates, code points beyond
// U+10FFFF) replaced by U+FFFD.
std::string_view valid_utf8(std::string_view text, std::string &repaired)
{
    std::size_t ascii = 0;
    while (ascii < text.size() && static_cast<unsigned char>(text[ascii]) < 0x80)
        ++ascii;
    if (ascii == text.size())
        return text;
    BoundedText in{text.data() + ascii, text.data() + text.size()};
    bool changed = false;
    repaired.assign(text.data(), ascii);
    while (in.at < in.end) {
        const char *start = in.at;
        unsigned code_point = 0;
        if (rapidjson::UTF8<>::Decode(in, &code_point)) {
            repaired.append(start, in.at);
        } else {
            repaired.append("\xEF\xBF\xBD"); // U+FFFD for the first byte,
            in.at = start + 1;               // then decode again after it
            changed = true;
        }
    }
    return changed ? std::string_view(repaired) : text;
}

} // namespace

struct JsonWriter::Rapid {
    rapidjson::StringBuffer buffer;
    std::optional<rapidjson::Writer<rapidjson::StringBuffer>> compact;
    std::optional<rapidjson::PrettyWriter<rapidjson::StringBuffer>> pretty;
    std::string repaired; // scratch for strings that are not valid UTF-8

    explicit Rapid(JsonLayout layout)
    {
        if (layout == JsonLayout::indented) {
            pretty.emplace(buffer);
            pretty->SetIndent(' ', 2);
            pretty->SetFormatOptions(rapidjson::kFormatSingleLineArray);
        } else {
            compact.emplace(buffer);
        }
    }

    // Calls `write` with whichever writer the layout chose.
    template <class F> void with(F &&write)
    {
        if (pretty)
            write(*pretty);
        else
            write(*compact);
    }

    bool complete() const { return pretty ? pretty->IsComplete() : compact->IsComplete(); }
};

JsonWriter::JsonWriter(AtomicFile &file, JsonLayout layout) : file_(&file), rapid_(std::make_unique<Rapid>(layout))
{
}

JsonWriter::JsonWriter(std::string &text, JsonLayout layout) : text_(&text), rapid_(std::make_unique<Rapid>(layout))
{
}

JsonWriter::~JsonWriter() = default;

JsonWriter::Scope::Scope(JsonWriter &writer, bool array)
    : writer_(&writer), array_(array), exceptions_(std::uncaught_exceptions())
{
}

JsonWriter::Scope::Scope(Scope &&other) noexcept
    : writer_(other.writer_), array_(other.array_), exceptions_(other.exceptions_)
{
    other.writer_ = nullptr;
}

JsonWriter::Scope::~Scope()
{
    if (writer_ && std::uncaught_exceptions() <= exceptions_)
        writer_->end(array_);
}

void JsonWriter::drain()
{
    rapidjson::StringBuffer &b = rapid_->buffer;
    if (b.GetSize() == 0)
        return;
    if (file_)
        file_->write(b.GetString(), b.GetSize());
    else
        text_->append(b.GetString(), b.GetSize());
    b.Clear();
}

JsonWriter::Scope JsonWriter::object()
{
    if (rapid_->buffer.GetSize() >= kDrainBytes)
        drain();
    rapid_->with([](auto &w) { w.StartObject(); });
    return Scope(*this, false);
}

JsonWriter::Scope JsonWriter::array()
{
    if (rapid_->buffer.GetSize() >= kDrainBytes)
        drain();
    rapid_->with([](auto &w) { w.StartArray(); });
    return Scope(*this, true);
}

JsonWriter::Scope JsonWriter::object(std::string_view k)
{
    key(k);
    return object();
}

JsonWriter::Scope JsonWriter::array(std::string_view k)
{
    key(k);
    return array();
}

void JsonWriter::end(bool array)
{
    // No draining here: this runs in destructors, which must not throw.
    if (array)
        rapid_->with([](auto &w) { w.EndArray(); });
    else
        rapid_->with([](auto &w) { w.EndObject(); });
}

void JsonWriter::key(std::string_view k)
{
    const std::string_view text = valid_utf8(k, rapid_->repaired);
    rapid_->with([&](auto &w) { w.Key(text.data(), static_cast<rapidjson::SizeType>(text.size()), false); });
}

void JsonWriter::value(double x)
{
    if (rapid_->buffer.GetSize() >= kDrainBytes)
        drain();
    if (!std::isfinite(x))
        rapid_->with([](auto &w) { w.Null(); });
    else if (x == std::trunc(x) && std::fabs(x) < kExactIntegers)
        rapid_->with([x](auto &w) { w.Int64(static_cast<int64_t>(x)); });
    else
        rapid_->with([x](auto &w) { w.Double(x); });
}

void JsonWriter::signed_value(int64_t x)
{
    if (rapid_->buffer.GetSize() >= kDrainBytes)
        drain();
    rapid_->with([x](auto &w) { w.Int64(x); });
}

void JsonWriter::unsigned_value(uint64_t x)
{
    if (rapid_->buffer.GetSize() >= kDrainBytes)
        drain();
    rapid_->with([x](auto &w) { w.Uint64(x); });
}

void JsonWriter::value(std::string_view s)
{
    if (rapid_->buffer.GetSize() >= kDrainBytes)
        drain();
    const std::string_view text = valid_utf8(s, rapid_->repaired);
    rapid_->with([&](auto &w) { w.String(text.data(), static_cast<rapidjson::SizeType>(text.size()), false); });
}

void JsonWriter::value(bool b)
{
    rapid_->with([b](auto &w) { w.Bool(b); });
}

void JsonWriter::null()
{
    rapid_->with([](auto &w) { w.Null(); });
}

void JsonWriter::finish()
{
    if (!rapid_->complete())
        throw std::logic_error("JSON document left incomplete (an object or array is still open)");
    drain();
}

void write_json_file(const std::filesystem::path &path, JsonLayout layout,
                     const std::function<void(JsonWriter &)> &members)
{
    AtomicFile file(path);
    JsonWriter j(file, layout);
    {
        const JsonWriter::Scope document = j.object();
        members(j);
    }
    j.finish();
    file.write("\n");
    file.commit();
}

} // namespace arbor::io
