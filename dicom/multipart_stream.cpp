#include "multipart_stream.hpp"

#include <algorithm>
#include <cctype>

namespace arbor::dicom {

std::string multipart_boundary(const std::string &content_type)
{
    std::string lower = content_type;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    std::size_t at = lower.find("boundary=");
    if (at == std::string::npos)
        return {};
    at += 9;
    if (at < content_type.size() && content_type[at] == '"') {
        const std::size_t end = content_type.find('"', at + 1);
        return end == std::string::npos ? std::string() : content_type.substr(at + 1, end - at - 1);
    }
    const std::size_t end = content_type.find_first_of("; \t\r\n", at);
    return content_type.substr(at, end == std::string::npos ? std::string::npos : end - at);
}

MultipartStream::MultipartStream(const std::string &boundary, PartCallback on_part)
    : delimiter_("\r\n--" + boundary), on_part_(std::move(on_part))
{
    // The body may begin with the delimiter itself, without the CRLF before it.
    buffer_ = "\r\n";
}

void MultipartStream::feed(const char *data, std::size_t size)
{
    if (done_)
        return; // the epilogue
    buffer_.append(data, size);
    parse();
}

void MultipartStream::parse()
{
    for (;;) {
        if (!started_) {
            const std::size_t at = buffer_.find(delimiter_);
            if (at == std::string::npos)
                return;
            buffer_.erase(0, at); // drop the preamble
            started_ = true;
        }
        // buffer_ starts with a delimiter: what follows tells close or part.
        const std::size_t after = delimiter_.size();
        if (buffer_.size() < after + 2)
            return;
        if (buffer_.compare(after, 2, "--") == 0) {
            done_ = true;
            buffer_.clear();
            return;
        }
        const std::size_t line_end = buffer_.find("\r\n", after);
        if (line_end == std::string::npos)
            return;
        const std::size_t headers_end = buffer_.find("\r\n\r\n", line_end);
        if (headers_end == std::string::npos)
            return;
        const std::size_t body = headers_end + 4;
        const std::size_t from = std::max(body, scanned_);
        const std::size_t next = buffer_.find(delimiter_, from);
        if (next == std::string::npos) {
            scanned_ = buffer_.size() > delimiter_.size() ? buffer_.size() - delimiter_.size() : 0;
            return;
        }
        // A part without headers has its blank line right after the delimiter's.
        const std::string headers =
            headers_end > line_end ? buffer_.substr(line_end + 2, headers_end - line_end - 2) : std::string();
        std::string part = buffer_.substr(body, next - body);
        buffer_.erase(0, next);
        scanned_ = 0;
        ++parts_;
        on_part_(headers, part);
    }
}

} // namespace arbor::dicom
