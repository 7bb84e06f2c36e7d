// multipart_stream.hpp - the parts of a multipart/related HTTP body (RFC
// 2046), as the bytes arrive: WADO-RS sends a series as one part per
// instance, and each is handed on as soon as it is whole, so a retrieve
// holds one instance in memory at a time and shows progress per image.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace arbor::dicom {

// The boundary parameter of a Content-Type header value ("" if none).
std::string multipart_boundary(const std::string &content_type);

class MultipartStream {
public:
    // on_part(headers, body): headers as sent (lines), body without the
    // CRLF before the next delimiter.
    using PartCallback = std::function<void(const std::string &headers, std::string &body)>;
    MultipartStream(const std::string &boundary, PartCallback on_part);

    void feed(const char *data, std::size_t size);
    // The closing delimiter arrived.
    bool finished() const { return done_; }
    int parts() const { return parts_; }

private:
    void parse();

    const std::string delimiter_; // "\r\n--" + boundary
    PartCallback on_part_;
    std::string buffer_;
    std::size_t scanned_ = 0; // where the search for the next delimiter resumes
    bool started_ = false, done_ = false;
    int parts_ = 0;
};

} // namespace arbor::dicom
