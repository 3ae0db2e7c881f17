#include "sinew/io/storage_file.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <omp.h>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "number_text.hpp"
#include "sinew/core/error.hpp"

namespace sinew {
namespace {

// A blank of a storage line: space, tab, or the CR of a CRLF line end. A plain test, not a search of a
// character set: it runs for every cell.
bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view trimRightView(std::string_view text) {
    std::size_t end = text.size();
    while (end > 0 && isBlank(text[end - 1])) --end;
    return text.substr(0, end);
}

std::string_view trimView(std::string_view text) {
    text = trimRightView(text);
    std::size_t begin = 0;
    while (begin < text.size() && isBlank(text[begin])) ++begin;
    return text.substr(begin);
}

std::string trimRight(const std::string& text) { return std::string(trimRightView(text)); }
std::string trim(const std::string& text) { return std::string(trimView(text)); }

bool isSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

// The cells of a header or data line, as views into it: tab-separated when the line has a tab (OpenSim's own
// files; a cell may then be empty), else separated by runs of white space (hand-written .mot files). Empty
// cells at the end of the line (trailing tabs) are dropped; a tab-separated line is then padded with empty
// cells to `minCells` (a line's trailing tabs are trimmed before it gets here, so a short row may be empty
// cells). `cells` is reused from row to row.
void splitCells(std::string_view line, std::vector<std::string_view>& cells, std::size_t minCells = 0) {
    cells.clear();
    if (line.find('\t') != std::string_view::npos) {
        for (std::size_t start = 0;;) {
            const std::size_t tab = line.find('\t', start);
            cells.push_back(trimView(line.substr(start, tab == std::string_view::npos ? std::string_view::npos : tab - start)));
            if (tab == std::string_view::npos || tab + 1 == line.size()) break;
            start = tab + 1;
        }
        while (!cells.empty() && cells.back().empty()) cells.pop_back();
        if (cells.size() < minCells) cells.resize(minCells);
    } else {
        for (std::size_t i = 0; i < line.size();) {
            while (i < line.size() && isSpace(line[i])) ++i;
            const std::size_t start = i;
            while (i < line.size() && !isSpace(line[i])) ++i;
            if (i > start) cells.push_back(line.substr(start, i - start));
        }
    }
}

// Reads one OpenSim storage file, turning every problem into an Error at "file:line".
class StorageReader {
public:
    StorageReader(std::string path, NonFinite nonFinite) : path_(std::move(path)), in_(path_), nonFinite_(nonFinite) {
        if (!in_) throw Error(path_ + ": cannot open for reading");
    }

    StorageTable read() {
        readHeader();
        readLabels();
        readRows();
        if (nRows_ && *nRows_ != static_cast<long>(table_.rows.size()))
            fail(nRowsLine_, "the header says nRows=" + std::to_string(*nRows_) + " but the table has " +
                                 std::to_string(table_.rows.size()) + " rows");
        return std::move(table_);
    }

private:
    std::string path_;
    std::ifstream in_;
    NonFinite nonFinite_;
    int lineNumber_ = 0;
    StorageTable table_;
    std::optional<long> nRows_, nColumns_;
    int nRowsLine_ = 0, nColumnsLine_ = 0;

    [[noreturn]] void fail(int line, const std::string& message) const {
        throw Error(path_ + ":" + std::to_string(line) + ": " + message);
    }

    bool nextLine(std::string& line) {
        if (!std::getline(in_, line)) return false;
        ++lineNumber_;
        line.resize(trimRightView(line).size());  // trailing blanks only: the leading ones stay
        return true;
    }

    long readCount(const std::string& key, const std::string& value, long minimum) const {
        char* end = nullptr;
        const long count = std::strtol(value.c_str(), &end, 10);
        if (value.empty() || end != value.c_str() + value.size() || count < minimum)
            fail(lineNumber_, key + "='" + value + "' is not an integer >= " + std::to_string(minimum));
        return count;
    }

    void readHeader() {
        std::string line;
        while (nextLine(line)) {
            if (trim(line) == "endheader") return;
            const std::size_t equals = line.find('=');
            if (equals == std::string::npos) {
                if (lineNumber_ == 1)
                    table_.name = line;
                else
                    table_.header.push_back(line);
                continue;
            }
            const std::string key = trim(line.substr(0, equals));
            const std::string value = trim(line.substr(equals + 1));
            if (key == "version") {
                readCount(key, value, 1);
            } else if (key == "nRows") {
                nRows_ = readCount(key, value, 0);
                nRowsLine_ = lineNumber_;
            } else if (key == "nColumns") {
                nColumns_ = readCount(key, value, 1);
                nColumnsLine_ = lineNumber_;
            } else if (key == "inDegrees") {
                if (value != "yes" && value != "no") fail(lineNumber_, "inDegrees='" + value + "', expected yes or no");
                table_.inDegrees = value == "yes";
            } else {
                if (key == "DataType" && value != "double")
                    fail(lineNumber_, "DataType=" + value + ": only tables of plain numbers (double) are read");
                table_.header.push_back(line);
            }
        }
        throw Error(path_ + ":" + std::to_string(lineNumber_) +
                    ": reached the end without an 'endheader' line; not an OpenSim storage file");
    }

    void readLabels() {
        std::string line;
        do {
            if (!nextLine(line)) fail(lineNumber_ + 1, "missing column labels after 'endheader'");
        } while (trim(line).empty());
        std::vector<std::string_view> cells;
        splitCells(line, cells);
        const std::vector<std::string> labels(cells.begin(), cells.end());
        // A line of other white space (a form feed, a vertical tab) is not blank to trim() but has no cells.
        if (labels.empty()) fail(lineNumber_, "missing column labels after 'endheader' (a line of white space only)");
        if (labels.front() != "time") fail(lineNumber_, "first column must be 'time', got '" + labels.front() + "'");
        for (std::size_t i = 1; i < labels.size(); ++i)
            if (labels[i].empty()) fail(lineNumber_, "column " + std::to_string(i + 1) + " has an empty label");
        if (nColumns_ && *nColumns_ != static_cast<long>(labels.size()))
            fail(lineNumber_, std::to_string(labels.size()) + " column labels (time included) but line " +
                                  std::to_string(nColumnsLine_) + " says nColumns=" + std::to_string(*nColumns_));
        table_.columns.assign(labels.begin() + 1, labels.end());
        table_.where = path_ + ":" + std::to_string(lineNumber_);
    }

    std::string describeColumn(std::size_t cell) const {
        if (cell == 0) return "column 1 'time'";
        if (cell <= table_.columns.size())
            return "column " + std::to_string(cell + 1) + " '" + table_.columns[cell - 1] + "'";
        return "column " + std::to_string(cell + 1) + " (beyond the " + std::to_string(table_.columns.size() + 1) +
               " labels)";
    }

    // The common row, `expected` short decimals (number_text.hpp) separated by tabs, blanks around them
    // allowed, read in one pass without splitting it into cells. False for any other line, which the cells
    // then read (and report): the values read here are those the cells would give.
    // `time` is the first cell's text.
    static bool readPlainRow(std::string_view line, std::size_t expected, std::vector<double>& values,
                             std::string_view& time) {
        values.clear();
        const char* p = line.data();
        const char* const end = p + line.size();
        while (true) {
            while (p != end && *p == ' ') ++p;
            const char* const start = p;
            double value = 0;
            p = readShortDecimal(p, end, value);
            if (!p) return false;
            if (values.empty()) time = std::string_view(start, static_cast<std::size_t>(p - start));
            values.push_back(value);
            while (p != end && *p == ' ') ++p;
            if (p == end) return values.size() == expected;
            if (*p++ != '\t') return false;
        }
    }

    void addRow(const std::vector<double>& values, std::string_view time) {
        if (!table_.times.empty() && !(values.front() > table_.times.back()))
            fail(lineNumber_, "time " + std::string(time) + " does not increase (the row before is at " +
                                  std::to_string(table_.times.back()) + ")");
        table_.rowLines.push_back(lineNumber_);
        table_.times.push_back(values.front());
        table_.rows.emplace_back(values.begin() + 1, values.end());
    }

    void readRows() {
        std::string line;
        std::vector<std::string_view> cells;
        std::vector<double> values;
        while (nextLine(line)) {
            if (trimView(line).empty()) continue;
            const std::size_t expected = table_.columns.size() + 1;
            const bool allowNonFinite = nonFinite_ == NonFinite::Allow;
            std::string_view time;
            if (readPlainRow(line, expected, values, time)) {
                addRow(values, time);
                continue;
            }
            splitCells(line, cells, allowNonFinite ? expected : 0);
            values.clear();
            for (std::size_t c = 0; c < cells.size(); ++c) {
                const std::string_view cell = cells[c];
                if (cell.empty() && allowNonFinite && c > 0) {
                    values.push_back(std::numeric_limits<double>::quiet_NaN());
                    continue;
                }
                if (cell.empty()) fail(lineNumber_, "empty cell in " + describeColumn(c));
                const std::optional<double> value = parseNumber(cell);
                if (!value) fail(lineNumber_, "'" + std::string(cell) + "' is not a number (" + describeColumn(c) + ")");
                if (!std::isfinite(*value) && (!allowNonFinite || c == 0))
                    fail(lineNumber_, "'" + std::string(cell) + "' is not a finite number (" + describeColumn(c) + ")");
                values.push_back(*value);
            }
            if (values.size() != expected)
                fail(lineNumber_, std::to_string(values.size()) + " values, expected " + std::to_string(expected) +
                                      (values.size() < expected ? "; the first missing is " : "; the first extra is ") +
                                      describeColumn(std::min(values.size(), expected)));
            addRow(values, cells.front());
        }
    }
};

// A header text the reader would not give back unchanged.
void checkHeaderText(const std::string& text, const std::string& what, const std::string& path) {
    if (text.find_first_of("\n\r") != std::string::npos || trimRight(text) != text || trim(text) == "endheader")
        throw Error(path + ": the " + what + " '" + text +
                    "' cannot be written (it holds a line break, ends in blanks or is 'endheader')");
}

// The shortest text that reads back as exactly `value` (decimals < 0), or `decimals` fixed decimals,
// appended to `text`. std::to_chars does either many times faster than a stream.
void appendNumber(std::string& text, double value, int decimals) {
    std::array<char, 512> buffer;  // a finite double in fixed notation has at most 309 integer digits
    const auto [end, error] = decimals < 0 ? std::to_chars(buffer.data(), buffer.data() + buffer.size(), value)
                                           : std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                                           std::chars_format::fixed, decimals);
    if (error == std::errc()) {
        text.append(buffer.data(), end);
    } else {
        std::ostringstream out;
        out << std::fixed << std::setprecision(decimals) << value;
        text += out.str();
    }
}

// Rows [first, end) as the file has them.
std::string formatRows(const StorageTable& table, std::size_t first, std::size_t end) {
    std::string text;
    text.reserve((end - first) * (table.columns.size() + 1) * 20);
    for (std::size_t i = first; i < end; ++i) {
        appendNumber(text, table.times[i], -1);
        for (double value : table.rows[i]) {
            text += '\t';
            appendNumber(text, value, table.decimals);
        }
        text += '\n';
    }
    return text;
}

// Below this many cells a table is formatted on the calling thread alone: a team's start costs more.
constexpr std::size_t kCellsFormattedInParallel = 1000;

}  // namespace

void writeStorageFile(const StorageTable& table, const std::string& path) {
    OutputFileSet set;
    writeStorageFile(table, set, path);
    set.commit();
}

void writeStorageFile(const StorageTable& table, OutputFileSet& set, const std::string& path) {
    // Everything is checked before the file is opened, so a refused table starts no file.
    checkHeaderText(table.name, "name", path);
    if (table.name.find('=') != std::string::npos)
        throw Error(path + ": the name '" + table.name + "' cannot be written: a first line with '=' reads as metadata");
    for (const std::string& line : table.header) checkHeaderText(line, "header line", path);
    for (const std::string& column : table.columns)
        if (column.empty() || column.find_first_of("\t\n\r") != std::string::npos || trim(column) != column)
            throw Error(path + ": the column label '" + column + "' is empty or holds a tab, line break or edge blank");
    if (table.times.size() != table.rows.size())
        throw Error(path + ": " + std::to_string(table.times.size()) + " times for " +
                    std::to_string(table.rows.size()) + " rows");
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        if (table.rows[i].size() != table.columns.size())
            throw Error(path + ": row " + std::to_string(i) + " has " + std::to_string(table.rows[i].size()) +
                        " values for " + std::to_string(table.columns.size()) + " columns");
        if (!std::isfinite(table.times[i])) throw Error(path + ": row " + std::to_string(i) + " has a non-finite time");
        for (std::size_t c = 0; c < table.columns.size(); ++c)
            if (!std::isfinite(table.rows[i][c]))
                throw Error(path + ": row " + std::to_string(i) + ", column '" + table.columns[c] +
                            "' is not finite");
    }

    std::ostream& out = set.open(path);
    out << table.name << "\nversion=1\nnRows=" << table.rows.size() << "\nnColumns=" << table.columns.size() + 1
        << "\ninDegrees=" << (table.inDegrees ? "yes" : "no") << '\n';
    for (const std::string& line : table.header) out << line << '\n';
    out << "endheader\ntime";
    for (const std::string& column : table.columns) out << '\t' << column;
    out << '\n';
    // Numbers are most of a table's writing (the shortest round-trip text of each): blocks of rows are
    // formatted side by side, then written in order.
    const std::size_t rows = table.rows.size();
    const bool parallel = rows * (table.columns.size() + 1) >= kCellsFormattedInParallel;
    const int blocks = parallel ? std::max(1, std::min(omp_get_max_threads(), static_cast<int>(rows))) : 1;
    std::vector<std::string> text(static_cast<std::size_t>(blocks));
#pragma omp parallel for num_threads(blocks) schedule(static, 1) if (parallel)
    for (int b = 0; b < blocks; ++b) {
        const std::size_t block = static_cast<std::size_t>(b), count = static_cast<std::size_t>(blocks);
        text[block] = formatRows(table, rows * block / count, rows * (block + 1) / count);
    }
    for (const std::string& block : text) out.write(block.data(), static_cast<std::streamsize>(block.size()));
}

StorageTable readStorageFile(const std::string& path, NonFinite nonFinite) {
    return StorageReader(path, nonFinite).read();
}

void checkStorageMagnitudes(const StorageTable& table, const std::vector<int>& columns, double bound,
                            const std::string& what) {
    for (std::size_t r = 0; r < table.rows.size(); ++r)
        for (int c : columns) {
            const double value = table.rows[r][static_cast<std::size_t>(c)];
            if (!(std::abs(value) > bound) || std::isnan(value)) continue;
            const std::string at = table.where.empty() || r >= table.rowLines.size()
                                       ? "storage table '" + table.name + "' row " + std::to_string(r)
                                       : table.where.substr(0, table.where.rfind(':')) + ":" +
                                             std::to_string(table.rowLines[r]);
            std::ostringstream text;
            text << at << ": column '" << table.columns[static_cast<std::size_t>(c)] << "' = " << value
                 << " (t = " << table.times[r] << " s) is beyond +-" << bound << " for " << what;
            throw Error(text.str());
        }
}

std::vector<int> matchStorageColumns(const StorageTable& table, const std::vector<std::string>& expected,
                                     ExtraColumns extra) {
    std::map<std::string, std::vector<int>> positions;
    for (std::size_t c = 0; c < table.columns.size(); ++c) positions[table.columns[c]].push_back(static_cast<int>(c));
    std::vector<int> indices;
    std::string missing, duplicated, unexpected;
    auto append = [](std::string& list, const std::string& item) { list += (list.empty() ? "" : ", ") + item; };
    for (const std::string& name : expected) {
        const auto found = positions.find(name);
        if (found == positions.end()) {
            append(missing, "'" + name + "'");
            indices.push_back(-1);
            continue;
        }
        if (found->second.size() > 1)
            append(duplicated, "'" + name + "' (" + std::to_string(found->second.size()) + " times)");
        indices.push_back(found->second.front());
    }
    if (extra == ExtraColumns::Refuse) {
        const std::set<std::string> wanted(expected.begin(), expected.end());
        for (const std::string& column : table.columns)
            if (!wanted.count(column)) append(unexpected, "'" + column + "'");
    }
    if (missing.empty() && duplicated.empty() && unexpected.empty()) return indices;
    std::string message = (table.where.empty() ? "storage table '" + table.name + "'" : table.where) +
                          ": the columns do not match the " + std::to_string(expected.size()) + " expected";
    if (!missing.empty()) message += "; missing " + missing;
    if (!duplicated.empty()) message += "; duplicated " + duplicated;
    if (!unexpected.empty()) message += "; not expected " + unexpected;
    throw Error(message);
}

}  // namespace sinew
