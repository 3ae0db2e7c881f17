#include "sinew/tools/model_loading.hpp"

#include "sinew/io/model_file.hpp"
#include "sinew/io/osim_model_converter.hpp"

namespace sinew {

Model loadModel(const std::string& path, const std::function<void(const std::string&)>& notes) {
    const bool osim = path.size() >= 5 && path.compare(path.size() - 5, 5, ".osim") == 0;
    if (!osim) return readModelFile(path);
    OsimConversion conversion = convertOsimModel(readOsimModel(path));
    if (notes)
        for (const std::string& line : conversion.notImported) notes("not imported: " + line);
    return std::move(conversion.model);
}

}  // namespace sinew
