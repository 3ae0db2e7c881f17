#include "sinew/io/storage_file.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "sinew/core/error.hpp"

namespace sinew {

void writeStorageFile(const StorageTable& table, const std::string& path) {
    std::ofstream out(path);
    if (!out) throw Error(path + ": cannot open for writing");
    out << table.name << "\nversion=1\nnRows=" << table.rows.size() << "\nnColumns=" << table.columns.size() + 1
        << "\ninDegrees=" << (table.inDegrees ? "yes" : "no") << "\nendheader\ntime";
    for (const std::string& column : table.columns) out << '\t' << column;
    out << '\n' << std::setprecision(17);
    for (std::size_t i = 0; i < table.rows.size(); ++i) {
        if (table.rows[i].size() != table.columns.size())
            throw Error(path + ": row " + std::to_string(i) + " has " + std::to_string(table.rows[i].size()) +
                        " values for " + std::to_string(table.columns.size()) + " columns");
        out << table.times[i];
        for (double value : table.rows[i]) out << '\t' << value;
        out << '\n';
    }
    if (!out) throw Error(path + ": write failed");
}

StorageTable readStorageFile(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open for reading");
    StorageTable table;
    std::string line;
    int lineNumber = 0;
    bool sawEnd = false;
    while (std::getline(in, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line == "endheader") {
            sawEnd = true;
            break;
        }
        if (lineNumber == 1) table.name = line;
        if (line.rfind("inDegrees=", 0) == 0) table.inDegrees = line.substr(10) == "yes";
    }
    if (!sawEnd)
        throw Error(path + ":" + std::to_string(lineNumber) + ": reached the end without an 'endheader' line; not an "
                    "OpenSim storage file");
    if (!std::getline(in, line)) throw Error(path + ":" + std::to_string(lineNumber + 1) + ": missing column labels");
    ++lineNumber;
    {
        std::istringstream labels(line);
        std::string label;
        std::getline(labels, label, '\t');
        if (label != "time")
            throw Error(path + ":" + std::to_string(lineNumber) + ": first column must be 'time', got '" + label + "'");
        while (std::getline(labels, label, '\t')) table.columns.push_back(label);
    }
    while (std::getline(in, line)) {
        ++lineNumber;
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        std::istringstream fields(line);
        std::vector<double> values;
        std::string field;
        while (fields >> field) {
            // strtod, unlike stod, accepts the subnormal numbers the writer can produce.
            char* end = nullptr;
            const double value = std::strtod(field.c_str(), &end);
            if (end != field.c_str() + field.size())
                throw Error(path + ":" + std::to_string(lineNumber) + ": '" + field + "' is not a number");
            values.push_back(value);
        }
        if (values.size() != table.columns.size() + 1)
            throw Error(path + ":" + std::to_string(lineNumber) + ": " + std::to_string(values.size()) +
                        " values, expected " + std::to_string(table.columns.size() + 1));
        table.times.push_back(values.front());
        table.rows.emplace_back(values.begin() + 1, values.end());
    }
    return table;
}

}  // namespace sinew
