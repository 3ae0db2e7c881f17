#pragma once
// The model census of the paper's Table 1.
#include "sinew/core/model.hpp"

namespace sinew {

struct Census {
    int links = 0;         // rigid links (bones grouped), excluding virtual links
    int virtualLinks = 0;  // massless 6-DOF links where forked wires meet
    int dof = 0;           // mobilities of the links (nu without virtual links)
    int dofWithVirtual = 0;  // nu
    int muscles = 0, tendons = 0, ligaments = 0, cartilage = 0;
    int wires = 0;
    int wirePoints = 0;
    int loops = 0;
    int forceElements = 0;  // limits, springs, bushings, contact forces (force_elements.hpp)
};

Census calcCensus(const Model& model);

}  // namespace sinew
