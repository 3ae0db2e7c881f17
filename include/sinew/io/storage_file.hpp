#pragma once
// OpenSim storage (.sto/.mot) tables: a header ending in `endheader`, then a table whose first column is
// time. Reads both header styles OpenSim writes (docs/opensim-files.md):
// - version 1: a name line, then version=1, nRows=, nColumns= (time included), inDegrees=yes|no, free text;
// - OpenSim 4 (file version 3): key=value lines (DataType=double, version=3, OpenSimVersion=..., any user
//   metadata), with or without a name line first.
// Written files use the version-1 header, which every OpenSim release reads.
#include <string>
#include <vector>

#include "sinew/io/atomic_file.hpp"

namespace sinew {

struct StorageTable {
    std::string name;                       // the header's first line, unless that line is key=value
    bool inDegrees = false;                 // angles in the table are in degrees
    std::vector<std::string> columns;       // labels without "time"
    std::vector<double> times;              // s, one per row
    std::vector<std::vector<double>> rows;  // rows[i].size() == columns.size()
    // The other header lines in file order, verbatim (trailing blanks trimmed): key=value metadata other
    // than version, nRows, nColumns and inDegrees, and free text. Written back as they are.
    std::vector<std::string> header = {};
    // "file:line" of the column labels when the table was read from a file, for messages; empty otherwise.
    std::string where = {};
    // The file line of each row when read from a file (rows[i] sits on line rowLines[i]); empty otherwise.
    std::vector<int> rowLines = {};
    // Written with this many digits after the point (fixed), for a file meant to be small; -1: the shortest
    // text that reads back bit for bit.
    int decimals = -1;
};

// Throws sinew::Error for a table that could not be read back: rows of the wrong length, a non-finite
// value, a label or header line that would break the layout; and for a failed write (a full disk), after
// which no file is left at `path` that was not there before (io/atomic_file.hpp).
void writeStorageFile(const StorageTable& table, const std::string& path);
// The same as one file of a command's output set, renamed into place with the others on set.commit().
void writeStorageFile(const StorageTable& table, OutputFileSet& set, const std::string& path);
enum class NonFinite { Refuse, Allow };

// Throws sinew::Error naming the file, line (and column, for a cell) of a malformed header or row;
// non-numeric cells are refused. NaN and infinite cells are refused by default; with NonFinite::Allow
// (for motions with gaps, which the caller then skips) they are read as they are, and in a tab-separated
// row an empty cell, or a cell missing at the end of the row, reads as NaN. Times must be finite either way.
StorageTable readStorageFile(const std::string& path, NonFinite nonFinite = NonFinite::Refuse);

// Refuses a finite cell of the given columns (indices into table.columns) beyond +-bound, naming the file
// and line (or the table and row), the column and `what` the column holds: a value no body produces, that
// would overflow the dynamics or the solvers (a ground reaction of 1e308 N, a coordinate of 1e300 degrees).
void checkStorageMagnitudes(const StorageTable& table, const std::vector<int>& columns, double bound,
                            const std::string& what);

enum class ExtraColumns { Allow, Refuse };

// Where each expected label sits: result[i] indexes table.columns for expected[i]. Throws sinew::Error at
// table.where listing every missing expected label, every expected label present more than once, and
// (with ExtraColumns::Refuse) every column that was not expected.
std::vector<int> matchStorageColumns(const StorageTable& table, const std::vector<std::string>& expected,
                                     ExtraColumns extra);

}  // namespace sinew
