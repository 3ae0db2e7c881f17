#include "sinew/io/atomic_file.hpp"

#include <fcntl.h>
#include <linux/fs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "sinew/core/error.hpp"

namespace sinew {

struct OutputFileSet::Entry {
    std::string path, temporary;  // temporary empty: written in place
    std::ofstream stream;
};

namespace {

std::string describeErrno() { return errno ? std::string(" (") + std::strerror(errno) + ")" : std::string(); }

// Puts `temporary` in place of `path`, atomically: a reader sees the old file or the new, never neither.
// An existing file is exchanged with the temporary, which is then removed: ext4 writes out a file renamed
// over another at once (its auto_da_alloc), which made a plain rename over an old result take three times
// as long (0.25 against 0.08 ms for a 33 kB .sto). Where the exchange is not supported, or nothing is there
// to exchange, the plain rename.
void replaceWith(const std::string& temporary, const std::string& path, std::error_code& ec) {
    ec.clear();
    if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, path.c_str(), RENAME_EXCHANGE) == 0) {
        std::filesystem::remove(temporary, ec);  // the old file; a failure leaves it, the result is in place
        ec.clear();
        return;
    }
    std::filesystem::rename(temporary, path, ec);
}

}  // namespace

OutputFileSet::OutputFileSet() = default;

OutputFileSet::~OutputFileSet() {
    if (committed_) return;
    for (const std::unique_ptr<Entry>& entry : entries_) {
        entry->stream.close();
        if (!entry->temporary.empty()) std::remove(entry->temporary.c_str());
    }
}

std::ostream& OutputFileSet::open(const std::string& path) {
    if (committed_) throw Error(path + ": the output set was already committed");
    auto entry = std::make_unique<Entry>();
    entry->path = path;
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    // A device or pipe cannot be replaced by a rename (and a temporary beside /dev/full would be a file in /dev).
    const bool inPlace = std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
    if (!inPlace) entry->temporary = path + ".incomplete-" + std::to_string(::getpid());
    errno = 0;
    entry->stream.open(inPlace ? path : entry->temporary, std::ios::out | std::ios::trunc);
    if (!entry->stream) throw Error(path + ": cannot open for writing" + describeErrno());
    entries_.push_back(std::move(entry));
    return entries_.back()->stream;
}

void OutputFileSet::retire(const std::string& path) { retired_.push_back(path); }

void OutputFileSet::commit() {
    for (const std::unique_ptr<Entry>& entry : entries_) {
        errno = 0;
        entry->stream.flush();
        if (entry->stream) entry->stream.close();
        if (entry->stream.fail()) throw Error(entry->path + ": write failed" + describeErrno() + "; nothing was written");
    }
    for (const std::unique_ptr<Entry>& entry : entries_) {
        if (entry->temporary.empty()) continue;
        std::error_code ec;
        replaceWith(entry->temporary, entry->path, ec);
        if (ec) throw Error(entry->path + ": cannot replace it (" + ec.message() + ")");
    }
    committed_ = true;
    for (const std::string& path : retired_) {
        bool written = false;
        for (const std::unique_ptr<Entry>& entry : entries_) written = written || entry->path == path;
        std::error_code ec;
        if (!written) std::filesystem::remove(path, ec);
    }
}

void writeFileAtomically(const std::string& path, const std::string& text) {
    OutputFileSet set;
    set.open(path) << text;
    set.commit();
}

}  // namespace sinew
