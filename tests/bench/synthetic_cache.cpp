#include "synthetic_cache.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <set>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

namespace arbor::bench {

namespace fs = std::filesystem;

namespace {

uint64_t raw_bytes(const SyntheticField &f)
{
    return static_cast<uint64_t>(f.size) * f.size * f.size * sizeof(float);
}

bool complete(const fs::path &raw, const SyntheticField &f)
{
    std::error_code ec;
    return fs::is_regular_file(raw, ec) && fs::file_size(raw, ec) == raw_bytes(f);
}

void write_header(const fs::path &nhdr, const SyntheticField &f)
{
    const fs::path tmp = nhdr.string() + ".tmp";
    {
        std::ofstream out(tmp);
        out << "NRRD0004\n"
            << "# " << f.name() << ": written by arbor_bench_topology for gen_volumes.py output\n"
            << "type: float\ndimension: 3\n"
            << "sizes: " << f.size << ' ' << f.size << ' ' << f.size << '\n'
            << "spacings: 1 1 1\nendian: little\nencoding: raw\n"
            << "data file: " << f.name() << ".raw\n";
        if (!out)
            throw std::runtime_error("cannot write " + tmp.string());
    }
    fs::rename(tmp, nhdr);
}

std::string join(const std::set<int64_t> &sizes)
{
    std::string s;
    for (int64_t n : sizes)
        s += (s.empty() ? "" : ",") + std::to_string(n);
    return s;
}

// Runs argv without a shell (no quoting issues with paths); throws unless it
// exits with 0.
void run_program(const std::vector<std::string> &args)
{
    std::vector<char *> argv;
    for (const std::string &a : args)
        argv.push_back(const_cast<char *>(a.c_str()));
    argv.push_back(nullptr);
    std::cout.flush();
    std::cerr.flush();
    const pid_t pid = fork();
    if (pid < 0)
        throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
        dup2(STDERR_FILENO, STDOUT_FILENO); // keep the table on stdout clean
        execvp(argv[0], argv.data());
        std::fprintf(stderr, "cannot run %s: %s\n", argv[0], std::strerror(errno));
        _exit(127);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error(args[0] + " " + args[1] + " failed (status " + std::to_string(status) + ")");
}

} // namespace

std::string SyntheticField::name() const
{
    const char *prefix = kind == SyntheticKind::Blobs ? "blobs_" : kind == SyntheticKind::BlobsNoise ? "blobsnoise_" : "random_";
    return prefix + std::to_string(size);
}

fs::path synthetic_header(const SyntheticSetup &setup, const SyntheticField &field)
{
    const fs::path shipped = setup.shipped_dir / (field.name() + ".nhdr");
    if (!setup.shipped_dir.empty() && fs::exists(shipped) &&
        complete(setup.shipped_dir / (field.name() + ".raw"), field))
        return shipped;
    const fs::path raw = setup.cache_dir / (field.name() + ".raw");
    const fs::path nhdr = setup.cache_dir / (field.name() + ".nhdr");
    if (!complete(raw, field))
        prepare_synthetic(setup, {field});
    if (!fs::exists(nhdr))
        write_header(nhdr, field);
    return nhdr;
}

void prepare_synthetic(const SyntheticSetup &setup, const std::vector<SyntheticField> &fields)
{
    std::set<int64_t> blob_sizes, random_sizes;
    for (const SyntheticField &f : fields) {
        const bool shipped = !setup.shipped_dir.empty() &&
                             fs::exists(setup.shipped_dir / (f.name() + ".nhdr")) &&
                             complete(setup.shipped_dir / (f.name() + ".raw"), f);
        if (shipped || complete(setup.cache_dir / (f.name() + ".raw"), f))
            continue;
        (f.kind == SyntheticKind::Random ? random_sizes : blob_sizes).insert(f.size);
    }
    if (blob_sizes.empty() && random_sizes.empty())
        return;
    if (!fs::exists(setup.generator))
        throw std::runtime_error("the generator " + setup.generator.string() + " is missing");

    // Generate into a private folder and move the finished files in: an
    // interrupted run leaves no truncated file under a final name, and the
    // generator's README.txt (rewritten per run) stays out of the cache.
    fs::create_directories(setup.cache_dir);
    const fs::path work = setup.cache_dir / (".generating-" + std::to_string(getpid()));
    fs::remove_all(work);
    fs::create_directories(work);
    std::cerr << "generating synthetic fields in " << setup.cache_dir.string() << " (blobs sizes {"
              << join(blob_sizes) << "}, random sizes {" << join(random_sizes) << "})..." << std::endl;
    try {
        run_program({setup.python, setup.generator.string(), work.string(), "--sizes=" + join(blob_sizes),
                     "--random-sizes=" + join(random_sizes)});
        for (const fs::directory_entry &e : fs::directory_iterator(work))
            if (e.path().extension() == ".raw")
                fs::rename(e.path(), setup.cache_dir / e.path().filename());
    } catch (...) {
        fs::remove_all(work);
        throw;
    }
    fs::remove_all(work);
    for (const SyntheticField &f : fields) {
        const fs::path raw = setup.cache_dir / (f.name() + ".raw");
        if (complete(raw, f) && !fs::exists(setup.cache_dir / (f.name() + ".nhdr")))
            write_header(setup.cache_dir / (f.name() + ".nhdr"), f);
    }
}

} // namespace arbor::bench
