#pragma once
// OpenSim's TRC marker files (docs/motion-capture.md): a header of three lines (PathFileType, a line of keys
// and a line of their values: DataRate, NumFrames, NumMarkers, Units, ...), a row of marker names (Frame#,
// Time, then each name followed by two empty cells), a row of coordinate labels (X1 Y1 Z1 ...), then one
// row per frame. Tab-separated; blank lines, trailing tabs and CRLF line endings are read as OpenSim does.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sinew {

struct MarkerTable {
    std::string source;                  // the file it was read from; empty when built in code
    std::vector<std::string> markers;    // marker names, in file order
    std::vector<int> frameNumbers;       // the file's Frame# column, one per frame
    std::vector<double> times;           // s, strictly increasing, one per frame
    // m, per frame a (3 x markers.size()) matrix in the file's axes (converted from the header's Units:
    // mm, cm, m); NaN where a sample is missing (an empty cell): flagged, never invented.
    std::vector<Eigen::Matrix3Xd> positions;
    double dataRate = 0;                 // Hz, the header's DataRate
    // The file line of each frame when read from a file (frame i sits on line frameLines[i]); empty otherwise.
    std::vector<int> frameLines = {};
};

// Throws sinew::Error naming "file:line" and the column (cell number, with the marker and axis it holds)
// of a malformed header or row: a missing header line or key, an unknown unit, a marker count other than
// NumMarkers, a frame count other than NumFrames, a cell that is not a number, a row with more cells than
// the labels, a time that does not increase. Empty cells, cells missing at the end of a row, and cells
// reading NaN are missing samples (NaN); infinite values are refused.
MarkerTable readTrcFile(const std::string& path);

// Writes the table with Units m and 17 significant digits, so readTrcFile gives back the same numbers
// bit for bit (NaN as empty cells). Throws sinew::Error, before any file is started, for a table that
// would not read back: sizes that disagree, a marker name that is empty, repeated or holds a tab or line
// break, a time that is not finite or does not increase, an infinite coordinate, a DataRate <= 0. A failed
// write leaves no file (io/atomic_file.hpp).
void writeTrcFile(const std::string& path, const MarkerTable& table);

}  // namespace sinew
