#pragma once
// sinew's model file: YAML, versioned by its `sinew_model:` key (docs/model-format.md).
#include <string>

#include "sinew/core/model.hpp"

namespace sinew {

constexpr int kModelFormatVersion = 1;

// Reads and validates a model file. Throws ModelError naming the file, line and field of any problem.
Model readModelFile(const std::string& path);
// The same from text; `sourceName` stands for the file name in messages.
Model readModelText(const std::string& text, const std::string& sourceName);

// Writes the model in the current format; reading it back gives an identical model.
void writeModelFile(const Model& model, const std::string& path);
std::string writeModelText(const Model& model);

}  // namespace sinew
