#pragma once
// Output files written as a set, so that a failed or interrupted run never leaves a file that looks whole.
// Each file is written to a temporary beside it ("<name>.incomplete-<pid>", same folder, so the rename
// stays on one file system), its stream state checked through flush and close (a full disk or /dev/full
// fails here), and only when every file of the set is complete are they all renamed into place (an old
// file exchanged with its replacement, then removed: a reader never finds the path missing). Files of
// the set that this run does not produce (retire()) are removed at the same point, so no previous run's
// file is left beside the new ones. A set destroyed uncommitted (an exception, a failed run) removes its
// temporaries and touches nothing else: the folder keeps the previous run's files as they were.
// Paths that are not regular files (/dev/stdout, /dev/full, a pipe) are written in place, errors checked.
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace sinew {

class OutputFileSet {
public:
    OutputFileSet();
    ~OutputFileSet();
    OutputFileSet(const OutputFileSet&) = delete;
    OutputFileSet& operator=(const OutputFileSet&) = delete;

    // The stream to write `path` through (a temporary beside it). Throws sinew::Error when it cannot be
    // created; creates no folder.
    std::ostream& open(const std::string& path);
    // `path` is part of the set but not written by this run: removed, if it exists, on commit().
    void retire(const std::string& path);
    // Closes every file, throwing sinew::Error naming the first that failed (nothing renamed then), then
    // renames them into place and removes the retired paths.
    void commit();

private:
    struct Entry;
    std::vector<std::unique_ptr<Entry>> entries_;
    std::vector<std::string> retired_;
    bool committed_ = false;
};

// A set of one: `text` into `path`.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace sinew
