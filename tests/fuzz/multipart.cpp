// multipart.cpp - fuzzes the multipart/related parser (dicom/multipart_stream)
// that splits a WADO-RS response into instances as the bytes arrive.
//
// Input: the Content-Type header value up to the first line feed, then the
// body.  The body is fed in chunks of 1, 2, ... 61 bytes (and again), so that
// delimiters fall across chunk boundaries as they do on a network.
#include "fuzz_support.hpp"

#include "dicom/multipart_stream.hpp"

#include <algorithm>
#include <string>
#include <string_view>

namespace {

constexpr std::size_t kLongestChunk = 61;

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, std::size_t size)
{
    const std::string_view input(reinterpret_cast<const char *>(data), size);
    const std::size_t line_end = input.find('\n');
    if (line_end == std::string_view::npos)
        return 0;
    const std::string boundary = arbor::dicom::multipart_boundary(std::string(input.substr(0, line_end)));
    if (boundary.empty())
        return 0; // the client refuses a response without one
    const std::string_view body = input.substr(line_end + 1);
    std::size_t delivered = 0;
    arbor::dicom::MultipartStream stream(boundary, [&](const std::string &headers, std::string &part) {
        delivered += headers.size() + part.size();
        if (delivered > body.size())
            arbor::fuzz::finding("the parts hold more bytes than the body");
    });
    std::size_t chunk = 1;
    for (std::size_t at = 0; at < body.size(); at += chunk, chunk = chunk % kLongestChunk + 1)
        stream.feed(body.data() + at, std::min(chunk, body.size() - at));
    return 0;
}
