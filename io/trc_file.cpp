#include "sinew/io/trc_file.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "number_text.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/atomic_file.hpp"

namespace sinew {
namespace {

// Every character isspace() takes, so that a line counted blank here splits into no cells there.
const char* const kBlanks = " \t\r\v\f";
const char* const kAxes = "XYZ";

std::string trim(const std::string& text) {
    const std::size_t begin = text.find_first_not_of(kBlanks);
    if (begin == std::string::npos) return {};
    return text.substr(begin, text.find_last_not_of(kBlanks) - begin + 1);
}

// The cells of a line, in place: tab-separated when the line has a tab (a cell may then be empty, which is
// how TRC files leave a sample out), else separated by runs of blanks. Cells are trimmed.
std::vector<std::string> splitCells(const std::string& line) {
    std::vector<std::string> cells;
    if (line.find('\t') != std::string::npos) {
        std::istringstream fields(line);
        std::string cell;
        while (std::getline(fields, cell, '\t')) cells.push_back(trim(cell));
    } else {
        std::istringstream fields(line);
        std::string cell;
        while (fields >> cell) cells.push_back(cell);
    }
    return cells;
}

std::optional<int> parseInteger(const std::string& cell) {
    if (cell.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const long value = std::strtol(cell.c_str(), &end, 10);
    if (end != cell.c_str() + cell.size() || errno == ERANGE || value < INT_MIN || value > INT_MAX) return std::nullopt;
    return static_cast<int>(value);
}

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

// File units per metre divisor: a value in the file divided by this is in metres. Division (not
// multiplication by 0.001) so that the conversion is correctly rounded.
std::optional<double> unitDivisor(const std::string& units) {
    const std::string name = lower(units);
    if (name == "mm") return 1000.0;
    if (name == "cm") return 100.0;
    if (name == "m") return 1.0;
    return std::nullopt;
}

// Reads one TRC file, turning every problem into an Error at "file:line".
class TrcReader {
public:
    explicit TrcReader(std::string path) : path_(std::move(path)), in_(path_) {
        if (!in_) throw Error(path_ + ": cannot open for reading");
        table_.source = path_;
    }

    MarkerTable read() {
        readFileType();
        readHeaderValues();
        readMarkerNames();
        readCoordinateLabels();
        readFrames();
        if (static_cast<long>(table_.times.size()) != numFrames_)
            fail(valuesLine_, headerColumn("NumFrames"),
                 "NumFrames=" + std::to_string(numFrames_) + " but the file has " +
                     std::to_string(table_.times.size()) + " frames");
        return std::move(table_);
    }

private:
    std::string path_;
    std::ifstream in_;
    int lineNumber_ = 0;
    MarkerTable table_;
    std::vector<std::string> keys_;
    int valuesLine_ = 0;
    long numFrames_ = 0;
    int numMarkers_ = 0;
    double unitDivisor_ = 1;

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw Error(path_ + ":" + std::to_string(line) + ": " + message);
    }
    [[noreturn]] void fail(int line, const std::string& column, const std::string& message) const {
        fail(line, column + ": " + message);
    }

    // Cells are numbered from 1, as a spreadsheet shows them.
    std::string headerColumn(const std::string& key) const {
        const auto found = std::find(keys_.begin(), keys_.end(), key);
        return "column " + std::to_string(found - keys_.begin() + 1) + " (" + key + ")";
    }
    std::string dataColumn(std::size_t cell) const {
        std::string text = "column " + std::to_string(cell + 1);
        if (cell == 0) return text + " (Frame#)";
        if (cell == 1) return text + " (Time)";
        const std::size_t marker = (cell - 2) / 3;
        if (marker >= table_.markers.size()) return text;
        return text + " (" + table_.markers[marker] + " " + kAxes[(cell - 2) % 3] + ")";
    }

    // The next line that is not blank, trailing blanks and CR trimmed; false at the end of the file.
    bool nextLine(std::string& line) {
        while (std::getline(in_, line)) {
            ++lineNumber_;
            const std::size_t end = line.find_last_not_of(kBlanks);
            if (end == std::string::npos) continue;
            line.erase(end + 1);
            return true;
        }
        return false;
    }
    std::vector<std::string> nextHeaderCells(const std::string& what) {
        std::string line;
        if (!nextLine(line)) fail(lineNumber_ + 1, "the file ends before the header's " + what);
        return splitCells(line);
    }

    void readFileType() {
        const std::vector<std::string> cells = nextHeaderCells("PathFileType line");
        if (cells.front() != "PathFileType")
            fail(lineNumber_, "column 1: '" + cells.front() + "', expected 'PathFileType'; not a TRC marker file");
    }

    void readHeaderValues() {
        keys_ = nextHeaderCells("line of keys (DataRate, NumFrames, NumMarkers, Units, ...)");
        const int keysLine = lineNumber_;
        const std::vector<std::string> values = nextHeaderCells("line of values under its keys (line " +
                                                                std::to_string(keysLine) + ")");
        valuesLine_ = lineNumber_;
        for (const char* key : {"DataRate", "NumFrames", "NumMarkers", "Units"})
            if (std::find(keys_.begin(), keys_.end(), key) == keys_.end())
                fail(keysLine, std::string("the header has no key '") + key +
                                   "' (expected a line of keys: DataRate, NumFrames, NumMarkers, Units, ...)");
        std::map<std::string, std::string> byKey;
        for (std::size_t k = 0; k < keys_.size(); ++k) {
            if (k >= values.size() || values[k].empty())
                fail(valuesLine_, "column " + std::to_string(k + 1) + " (" + keys_[k] + ")",
                     "no value under the key '" + keys_[k] + "' of line " + std::to_string(keysLine));
            byKey[keys_[k]] = values[k];
        }
        auto value = [&](const std::string& key) { return byKey.at(key); };
        const std::optional<double> rate = parseNumber(value("DataRate"));
        if (!rate || !std::isfinite(*rate) || *rate <= 0)
            fail(valuesLine_, headerColumn("DataRate"), "'" + value("DataRate") + "' is not a positive number (Hz)");
        table_.dataRate = *rate;
        const std::optional<int> frames = parseInteger(value("NumFrames"));
        if (!frames || *frames < 0)
            fail(valuesLine_, headerColumn("NumFrames"), "'" + value("NumFrames") + "' is not an integer >= 0");
        numFrames_ = *frames;
        const std::optional<int> markers = parseInteger(value("NumMarkers"));
        if (!markers || *markers < 1)
            fail(valuesLine_, headerColumn("NumMarkers"), "'" + value("NumMarkers") + "' is not an integer >= 1");
        // Not reserved from the header: a NumMarkers of 2e9 would ask for 64 GB before the names are counted.
        numMarkers_ = *markers;
        const std::optional<double> divisor = unitDivisor(value("Units"));
        if (!divisor)
            fail(valuesLine_, headerColumn("Units"), "unknown Units '" + value("Units") + "', expected mm, cm or m");
        unitDivisor_ = *divisor;
    }

    void readMarkerNames() {
        const std::vector<std::string> cells = nextHeaderCells("row of marker names (Frame#, Time, names)");
        if (cells.size() < 2 || cells[0] != "Frame#" || cells[1] != "Time")
            fail(lineNumber_, "expected the row of marker names, starting 'Frame#' and 'Time', got '" +
                                  cells.front() + "'");
        std::map<std::string, std::size_t> columnOf;
        for (std::size_t c = 2; c < cells.size(); ++c) {
            if (cells[c].empty()) continue;
            const auto [at, inserted] = columnOf.emplace(cells[c], c);
            if (!inserted)
                fail(lineNumber_, "column " + std::to_string(c + 1),
                     "marker '" + cells[c] + "' is named twice (first in column " + std::to_string(at->second + 1) + ")");
            table_.markers.push_back(cells[c]);
        }
        if (static_cast<int>(table_.markers.size()) != numMarkers_)
            fail(lineNumber_, std::to_string(table_.markers.size()) + " marker names but line " +
                                  std::to_string(valuesLine_) + " " + headerColumn("NumMarkers") +
                                  " says NumMarkers=" + std::to_string(numMarkers_));
    }

    // The X1 Y1 Z1 ... row: only its count is checked (writers name the axes differently), and that it is
    // not already a row of numbers, which would mean the row is missing.
    void readCoordinateLabels() {
        const std::vector<std::string> cells = nextHeaderCells("row of coordinate labels (X1 Y1 Z1 ...)");
        std::size_t labels = 0;
        for (std::size_t c = 2; c < cells.size(); ++c) labels += !cells[c].empty();
        const bool numeric = cells.size() > 2 && parseNumber(cells[2]).has_value();
        if (numeric || labels != 3 * table_.markers.size())
            fail(lineNumber_, "expected the row of " + std::to_string(3 * table_.markers.size()) +
                                  " coordinate labels (X1 Y1 Z1 ... for NumMarkers=" +
                                  std::to_string(table_.markers.size()) + "), got " +
                                  (numeric ? "a row of numbers" : std::to_string(labels) + " labels"));
    }

    void readFrames() {
        const std::size_t expected = 2 + 3 * table_.markers.size();
        const auto markers = static_cast<Eigen::Index>(table_.markers.size());
        std::string line;
        while (nextLine(line)) {
            const std::vector<std::string> cells = splitCells(line);
            if (cells.size() > expected)
                fail(lineNumber_, "column " + std::to_string(expected + 1),
                     std::to_string(cells.size()) + " cells, but the header's " + std::to_string(markers) +
                         " markers make " + std::to_string(expected) + " columns (Frame#, Time, X Y Z each)");
            const std::optional<int> frame = parseInteger(cells[0]);
            if (!frame) fail(lineNumber_, dataColumn(0), "'" + cells[0] + "' is not an integer frame number");
            const std::optional<double> time = cells.size() > 1 ? parseNumber(cells[1]) : std::nullopt;
            if (!time || !std::isfinite(*time))
                fail(lineNumber_, dataColumn(1),
                     "'" + (cells.size() > 1 ? cells[1] : std::string()) + "' is not a finite time");
            if (!table_.times.empty() && !(*time > table_.times.back())) {
                std::ostringstream before;
                before << std::setprecision(17) << table_.times.back();
                fail(lineNumber_, dataColumn(1),
                     "time " + cells[1] + " does not increase (line " + std::to_string(table_.frameLines.back()) +
                         " is at " + before.str() + ")");
            }
            Eigen::Matrix3Xd positions(3, markers);
            for (std::size_t c = 2; c < expected; ++c) {
                const std::string cell = c < cells.size() ? cells[c] : std::string();
                double value = std::numeric_limits<double>::quiet_NaN();
                if (!cell.empty() && lower(cell) != "nan") {
                    const std::optional<double> number = parseNumber(cell);
                    if (!number) fail(lineNumber_, dataColumn(c), "'" + cell + "' is not a number");
                    if (!std::isfinite(*number)) fail(lineNumber_, dataColumn(c), "'" + cell + "' is not finite");
                    value = *number / unitDivisor_;
                }
                positions(static_cast<Eigen::Index>((c - 2) % 3), static_cast<Eigen::Index>((c - 2) / 3)) = value;
            }
            table_.frameNumbers.push_back(*frame);
            table_.times.push_back(*time);
            table_.positions.push_back(std::move(positions));
            table_.frameLines.push_back(lineNumber_);
        }
    }
};

void checkWritable(const std::string& path, const MarkerTable& table) {
    auto refuse = [&](const std::string& message) { throw Error(path + ": " + message); };
    if (table.markers.empty()) refuse("a marker table with no markers cannot be written");
    std::map<std::string, std::size_t> seen;
    for (std::size_t m = 0; m < table.markers.size(); ++m) {
        const std::string& name = table.markers[m];
        if (name.empty() || trim(name) != name || name.find_first_of("\t\n\r") != std::string::npos)
            refuse("marker " + std::to_string(m) + " '" + name +
                   "' is empty or holds a tab, line break or edge blank");
        if (!seen.emplace(name, m).second) refuse("marker '" + name + "' is named twice");
    }
    if (!std::isfinite(table.dataRate) || table.dataRate <= 0) refuse("DataRate must be a positive number of Hz");
    const std::size_t frames = table.times.size();
    if (table.frameNumbers.size() != frames || table.positions.size() != frames)
        refuse(std::to_string(frames) + " times, " + std::to_string(table.frameNumbers.size()) + " frame numbers and " +
               std::to_string(table.positions.size()) + " position matrices; expected one each per frame");
    for (std::size_t i = 0; i < frames; ++i) {
        if (!std::isfinite(table.times[i]) || (i > 0 && !(table.times[i] > table.times[i - 1])))
            refuse("frame " + std::to_string(i) + ": the time is not finite or does not increase");
        if (table.positions[i].cols() != static_cast<Eigen::Index>(table.markers.size()))
            refuse("frame " + std::to_string(i) + " has " + std::to_string(table.positions[i].cols()) +
                   " marker columns for " + std::to_string(table.markers.size()) + " markers");
        if ((table.positions[i].array().abs() == std::numeric_limits<double>::infinity()).any())
            refuse("frame " + std::to_string(i) + " has an infinite coordinate");
    }
}

}  // namespace

MarkerTable readTrcFile(const std::string& path) { return TrcReader(path).read(); }

void writeTrcFile(const std::string& path, const MarkerTable& table) {
    checkWritable(path, table);
    const std::size_t frames = table.times.size();
    OutputFileSet set;
    std::ostream& out = set.open(path);
    out << std::setprecision(17);
    out << "PathFileType\t4\t(X/Y/Z)\t" << std::filesystem::path(path).filename().string() << '\n'
        << "DataRate\tCameraRate\tNumFrames\tNumMarkers\tUnits\tOrigDataRate\tOrigDataStartFrame\tOrigNumFrames\n"
        << table.dataRate << '\t' << table.dataRate << '\t' << frames << '\t' << table.markers.size() << "\tm\t"
        << table.dataRate << '\t' << (frames ? table.frameNumbers.front() : 1) << '\t' << frames << '\n';
    out << "Frame#\tTime";
    for (const std::string& name : table.markers) out << '\t' << name << "\t\t";
    out << "\n\t";
    for (std::size_t m = 1; m <= table.markers.size(); ++m) out << "\tX" << m << "\tY" << m << "\tZ" << m;
    out << "\n\n";
    for (std::size_t i = 0; i < frames; ++i) {
        out << table.frameNumbers[i] << '\t' << table.times[i];
        const Eigen::Matrix3Xd& positions = table.positions[i];
        for (Eigen::Index m = 0; m < positions.cols(); ++m)
            for (Eigen::Index axis = 0; axis < 3; ++axis) {
                out << '\t';
                if (!std::isnan(positions(axis, m))) out << positions(axis, m);
            }
        out << '\n';
    }
    set.commit();
}

}  // namespace sinew
