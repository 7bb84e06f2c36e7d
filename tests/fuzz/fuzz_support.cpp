// fuzz_support.cpp - see fuzz_support.hpp.
#include "fuzz_support.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <typeinfo>

#include <cxxabi.h>
#include <unistd.h>

namespace arbor::fuzz {

namespace fs = std::filesystem;

namespace {

fs::path make_scratch_folder()
{
    const char *tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/arbor-fuzz-XXXXXX";
    if (!::mkdtemp(pattern.data())) {
        std::perror("arbor fuzz: mkdtemp");
        std::abort();
    }
    return pattern;
}

void remove_scratch_folder()
{
    std::error_code ec;
    fs::remove_all(scratch_folder(), ec);
}

std::string type_name(const std::type_info &type)
{
    int status = 0;
    char *name = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
    std::string out = status == 0 && name ? name : type.name();
    std::free(name);
    return out;
}

} // namespace

const fs::path &scratch_folder()
{
    static const fs::path folder = [] {
        fs::path f = make_scratch_folder();
        std::atexit(&remove_scratch_folder);
        return f;
    }();
    return folder;
}

fs::path write_input(const std::string &name, const uint8_t *data, std::size_t size)
{
    const fs::path path = scratch_folder() / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out)
        finding("cannot write the input to " + path.string() + " (the harness, not the parser)");
    return path;
}

std::vector<std::string_view> split_input(const uint8_t *data, std::size_t size, std::string_view separator)
{
    const std::string_view all(reinterpret_cast<const char *>(data), size);
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    for (;;) {
        const std::size_t at = all.find(separator, start);
        if (at == std::string_view::npos) {
            parts.push_back(all.substr(start));
            return parts;
        }
        parts.push_back(all.substr(start, at - start));
        start = at + separator.size();
    }
}

void finding(const std::string &what)
{
    std::fprintf(stderr, "FINDING: %s\n", what.c_str());
    std::fflush(stderr);
    std::abort();
}

void unexpected_exception(std::exception_ptr e)
{
    try {
        std::rethrow_exception(e);
    } catch (const std::exception &x) {
        finding("unexpected exception " + type_name(typeid(x)) + ": " + x.what());
    } catch (...) {
        finding("unexpected exception of a type not derived from std::exception");
    }
}

} // namespace arbor::fuzz
