// OpenSim storage tables (.sto/.mot, io/storage_file.hpp) and ExternalLoads (io/external_loads.hpp).
// StorageTable keeps its rows as vectors of rows, so `data` and `times` are copies to and from NumPy.
#include "bindings.hpp"
#include "sinew/core/error.hpp"
#include "sinew/io/external_loads.hpp"
#include "sinew/io/storage_file.hpp"

namespace sinew::python {
namespace {

Eigen::MatrixXd getData(const StorageTable& table) {
    Eigen::MatrixXd data(static_cast<Eigen::Index>(table.rows.size()), static_cast<Eigen::Index>(table.columns.size()));
    for (Eigen::Index i = 0; i < data.rows(); ++i) {
        const std::vector<double>& row = table.rows[static_cast<std::size_t>(i)];
        if (static_cast<Eigen::Index>(row.size()) != data.cols())
            throw Error("storage table '" + table.name + "': row " + std::to_string(i) + " has " +
                        std::to_string(row.size()) + " values for " + std::to_string(data.cols()) + " columns");
        for (Eigen::Index j = 0; j < data.cols(); ++j) data(i, j) = row[static_cast<std::size_t>(j)];
    }
    return data;
}

void setData(StorageTable& table, const Eigen::MatrixXd& data) {
    table.rows.assign(static_cast<std::size_t>(data.rows()), std::vector<double>(static_cast<std::size_t>(data.cols())));
    for (Eigen::Index i = 0; i < data.rows(); ++i)
        for (Eigen::Index j = 0; j < data.cols(); ++j) table.rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = data(i, j);
}

}  // namespace

void bindStorage(py::module_& m) {
    py::class_<StorageTable>(m, "StorageTable",
                             "An OpenSim storage table: times (rows), columns (labels without time), data "
                             "(rows x columns). writeStorageFile checks it when written.")
        .def(py::init([](std::vector<std::string> columns, const Eigen::VectorXd& times, const Eigen::MatrixXd& data,
                         std::string name, bool inDegrees) {
                 if (data.rows() != times.size() || data.cols() != static_cast<Eigen::Index>(columns.size()))
                     throw Error("StorageTable: data is " + std::to_string(data.rows()) + " x " +
                                 std::to_string(data.cols()) + "; expected " + std::to_string(times.size()) +
                                 " times x " + std::to_string(columns.size()) + " columns");
                 StorageTable table;
                 table.name = std::move(name);
                 table.inDegrees = inDegrees;
                 table.columns = std::move(columns);
                 table.times.assign(times.data(), times.data() + times.size());
                 setData(table, data);
                 return table;
             }),
             py::arg("columns"), py::arg("times"), py::arg("data"), py::arg("name") = "", py::arg("in_degrees") = false)
        .def_readwrite("name", &StorageTable::name)
        .def_readwrite("in_degrees", &StorageTable::inDegrees)
        .def_readwrite("columns", &StorageTable::columns)
        .def_readwrite("header", &StorageTable::header)
        .def_readwrite("decimals", &StorageTable::decimals)
        .def_readonly("where", &StorageTable::where)
        .def_property(
            "times",
            [](const StorageTable& t) { return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(t.times.data(), static_cast<Eigen::Index>(t.times.size()))); },
            [](StorageTable& t, const Eigen::VectorXd& times) { t.times.assign(times.data(), times.data() + times.size()); })
        .def_property("data", &getData, &setData, "rows x columns, a copy")
        .def(
            "column",
            [](const StorageTable& t, const std::string& label) {
                const auto j = static_cast<std::size_t>(matchStorageColumns(t, {label}, ExtraColumns::Allow)[0]);
                Eigen::VectorXd column(static_cast<Eigen::Index>(t.rows.size()));
                for (std::size_t i = 0; i < t.rows.size(); ++i) column[static_cast<Eigen::Index>(i)] = t.rows[i].at(j);
                return column;
            },
            "The values of one column (times.size()); raises sinew.Error naming the table when it is absent.")
        .def("__len__", [](const StorageTable& t) { return t.times.size(); })
        .def("__repr__", [](const StorageTable& t) {
            return "<sinew.StorageTable '" + t.name + "': " + std::to_string(t.times.size()) + " rows, " +
                   std::to_string(t.columns.size()) + " columns>";
        });

    m.def(
        "read_storage_file",
        [](const std::string& path, bool allowNonFinite) {
            return readStorageFile(path, allowNonFinite ? NonFinite::Allow : NonFinite::Refuse);
        },
        py::arg("path"), py::arg("allow_non_finite") = false,
        "Reads a .sto/.mot file; raises sinew.Error naming file:line of a malformed header or row.");
    m.def("write_storage_file", py::overload_cast<const StorageTable&, const std::string&>(&writeStorageFile),
          py::arg("table"), py::arg("path"), "Writes the table (version-1 header); nothing is left behind on failure.");

    py::class_<ExternalLoads>(m, "ExternalLoads", "OpenSim ExternalLoads: the XML and its data table.")
        .def_readonly("name", &ExternalLoads::name)
        .def_readonly("file", &ExternalLoads::file)
        .def_readonly("data_file", &ExternalLoads::dataFile)
        .def_readonly("data", &ExternalLoads::data)
        .def_property_readonly("bodies", [](const ExternalLoads& loads) {
            std::vector<std::string> bodies;
            for (const ExternalForce& force : loads.forces) bodies.push_back(force.appliedToBody);
            return bodies;
        });
    m.def("read_external_loads", &readExternalLoads, py::arg("path"),
          "Reads an OpenSim ExternalLoads XML and its data file.");
}

}  // namespace sinew::python
