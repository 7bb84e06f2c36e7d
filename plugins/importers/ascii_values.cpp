// ascii_values.cpp - see ascii_values.hpp.
#include "ascii_values.hpp"

#include "number_text.hpp"
#include "text_scan.hpp"

#include <arbor/sdk/error.hpp>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace arbor::importers {

namespace {

constexpr std::size_t kChunk = std::size_t{1} << 20;
// No number needs more characters; a longer word is garbage, not a number.
constexpr std::size_t kMaxWord = 128;

bool is_separator(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v' || c == ',';
}

template <class T>
void store(void *dest, uint64_t index, T value)
{
    std::memcpy(static_cast<unsigned char *>(dest) + index * sizeof(T), &value, sizeof(T));
}

// An integer voxel type: accepts "12", "-3" and integral reals like "12.0".
template <class T>
bool store_integer(std::string_view word, void *dest, uint64_t index)
{
    if (const std::optional<int64_t> i = parse_integer(word)) {
        if (*i < static_cast<int64_t>(std::numeric_limits<T>::min()) ||
            (*i > 0 &&
             static_cast<uint64_t>(*i) > static_cast<uint64_t>(std::numeric_limits<T>::max())))
            return false;
        store(dest, index, static_cast<T>(*i));
        return true;
    }
    const std::optional<double> r = parse_real(word);
    if (!r || !std::isfinite(*r) || *r != std::floor(*r))
        return false;
    if (*r < static_cast<double>(std::numeric_limits<T>::min()) ||
        *r > static_cast<double>(std::numeric_limits<T>::max()))
        return false;
    store(dest, index, static_cast<T>(*r));
    return true;
}

bool store_value(arbor_voxel_type type, std::string_view word, void *dest, uint64_t index)
{
    switch (type) {
    case ARBOR_VOXEL_U8: return store_integer<uint8_t>(word, dest, index);
    case ARBOR_VOXEL_I8: return store_integer<int8_t>(word, dest, index);
    case ARBOR_VOXEL_U16: return store_integer<uint16_t>(word, dest, index);
    case ARBOR_VOXEL_I16: return store_integer<int16_t>(word, dest, index);
    case ARBOR_VOXEL_U32: return store_integer<uint32_t>(word, dest, index);
    case ARBOR_VOXEL_I32: return store_integer<int32_t>(word, dest, index);
    case ARBOR_VOXEL_F32: {
        const std::optional<double> r = parse_real(word);
        if (!r || (std::isfinite(*r) && std::fabs(*r) > std::numeric_limits<float>::max()))
            return false;
        store(dest, index, static_cast<float>(*r));
        return true;
    }
    case ARBOR_VOXEL_F64: {
        const std::optional<double> r = parse_real(word);
        if (!r)
            return false;
        store(dest, index, *r);
        return true;
    }
    default: return false;
    }
}

} // namespace

void read_ascii_values(const DataFile &file, uint64_t offset, arbor_voxel_type type, void *dest,
                       uint64_t count, const sdk::Task &task)
{
    std::vector<char> chunk(kChunk);
    std::string word;
    uint64_t index = 0;
    uint64_t at = offset;
    const auto finish_word = [&] {
        if (word.empty())
            return;
        if (!store_value(type, word, dest, index))
            sdk::fail(ARBOR_ERROR_FORMAT, "value " + std::to_string(index + 1) +
                                              " in the ASCII voxel data of " + file.name() + ", " +
                                              excerpt(word) + ", is not a " +
                                              arbor_voxel_type_name(type) + " number");
        ++index;
        word.clear();
    };
    while (index < count) {
        const std::size_t got = file.read_at(at, chunk.data(), chunk.size());
        if (got == 0)
            break;
        at += got;
        for (std::size_t i = 0; i < got && index < count; ++i) {
            const char c = chunk[i];
            if (is_separator(c)) {
                finish_word();
            } else {
                if (word.size() >= kMaxWord)
                    sdk::fail(ARBOR_ERROR_FORMAT, "value " + std::to_string(index + 1) +
                                                      " in the ASCII voxel data of " + file.name() +
                                                      ", " + excerpt(word) + ", is not a number");
                word += c;
            }
        }
        task.progress(static_cast<double>(index) / static_cast<double>(count), "parsing");
    }
    if (index < count)
        finish_word();
    if (index < count)
        sdk::fail(ARBOR_ERROR_FORMAT, file.name() + " has " + std::to_string(index) +
                                          " ASCII values of voxel data, the header needs " +
                                          std::to_string(count));
}

} // namespace arbor::importers
