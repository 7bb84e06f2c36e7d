#include "pacs_input.hpp"

#include <cstdlib>
#include <fcntl.h>
#include <stdexcept>
#include <sys/file.h>
#include <unistd.h>

namespace arbor::dicom {

namespace fs = std::filesystem;

namespace {

const char *const kScheme = "pacs://";

const char *environment(const char *name)
{
    const char *v = std::getenv(name);
    return v && *v ? v : nullptr;
}

// An exclusive lock on a file for the life of the object.
class FolderLock {
public:
    explicit FolderLock(const fs::path &file) : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644))
    {
        if (fd_ >= 0)
            ::flock(fd_, LOCK_EX);
    }
    ~FolderLock()
    {
        if (fd_ >= 0)
            ::close(fd_); // releases the lock
    }
    FolderLock(const FolderLock &) = delete;
    FolderLock &operator=(const FolderLock &) = delete;

private:
    int fd_;
};

} // namespace

bool is_pacs_uri(const std::string &text)
{
    return text.rfind(kScheme, 0) == 0;
}

PacsUri parse_pacs_uri(const std::string &text)
{
    const std::string rest = text.substr(std::string(kScheme).size());
    const std::size_t slash = rest.rfind('/');
    PacsUri u;
    if (slash != std::string::npos) {
        u.node = rest.substr(0, slash);
        u.series_uid = rest.substr(slash + 1);
    }
    if (u.node.empty() || u.series_uid.empty())
        throw std::invalid_argument("'" + text + "' is not a PACS input: write pacs://NODE/SERIES_UID (NODE a name "
                                                 "from `arbor pacs nodes`, AET@host:port or a DICOMweb URL)");
    if (u.series_uid.size() > 64 || u.series_uid.find_first_not_of("0123456789.") != std::string::npos)
        throw std::invalid_argument("'" + u.series_uid + "' in " + text + " is not a Series Instance UID (digits and dots)");
    return u;
}

fs::path default_pacs_cache_folder()
{
    if (const char *dir = environment("ARBOR_PACS_CACHE_DIR"))
        return dir;
    const fs::path tail = fs::path("arbor") / "pacs";
    if (const char *xdg = environment("XDG_CACHE_HOME"); xdg && fs::path(xdg).is_absolute())
        return xdg / tail;
    if (const char *home = environment("HOME"))
        return fs::path(home) / ".cache" / tail;
    throw std::runtime_error("no folder for retrieved series: set ARBOR_PACS_CACHE_DIR, XDG_CACHE_HOME or HOME");
}

fs::path fetch_pacs_series(const std::string &uri, const PacsOptions &options, const RetrievalCallback &progress,
                           const fs::path &cache_folder, const fs::path &nodes_file)
{
    const PacsUri u = parse_pacs_uri(uri);
    const PacsNode node = find_node(u.node, read_nodes(nodes_file));
    const fs::path node_folder = cache_folder / node.cache_key();
    const fs::path folder = node_folder / u.series_uid;
    std::error_code ec;
    fs::create_directories(node_folder, ec);
    if (ec)
        throw std::runtime_error("cannot create the PACS cache folder " + node_folder.string() + ": " + ec.message());
    const FolderLock lock(node_folder / ("." + u.series_uid + ".lock"));
    if (retrieval_complete(folder, u.series_uid))
        return folder;
    const std::unique_ptr<PacsClient> client = connect(node, options);
    retrieve_series(*client, node, u.series_uid, RetrieveMethod::Get, folder, progress);
    return folder;
}

} // namespace arbor::dicom
