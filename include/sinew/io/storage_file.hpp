#pragma once
// OpenSim storage (.sto/.mot) tables: a header ending in `endheader`, then a tab-separated table whose
// first column is time.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace sinew {

struct StorageTable {
    std::string name;
    bool inDegrees = false;
    std::vector<std::string> columns;  // without "time"
    std::vector<double> times;         // s
    std::vector<std::vector<double>> rows;  // rows[i].size() == columns.size()
};

void writeStorageFile(const StorageTable& table, const std::string& path);
// Throws sinew::Error naming the file and line of a malformed header or row.
StorageTable readStorageFile(const std::string& path);

}  // namespace sinew
