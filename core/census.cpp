#include "sinew/core/census.hpp"

namespace sinew {

Census calcCensus(const Model& model) {
    Census census;
    for (int i = 0; i < model.getNumLinks(); ++i) {
        const bool isVirtual = model.getLink(i).isVirtual;
        (isVirtual ? census.virtualLinks : census.links) += 1;
        if (!isVirtual) census.dof += model.getJoint(i).nu;
    }
    census.dofWithVirtual = model.getNumU();
    for (const Wire& wire : model.getWires()) {
        switch (wire.kind) {
            case WireKind::Muscle: ++census.muscles; break;
            case WireKind::Tendon: ++census.tendons; break;
            case WireKind::Ligament: ++census.ligaments; break;
            case WireKind::Cartilage: ++census.cartilage; break;
        }
    }
    census.wires = model.getNumWires();
    census.wirePoints = static_cast<int>(model.getWirePoints().size());
    census.loops = model.getNumLoops();
    const ForceElements& elements = model.getForceElements();
    census.forceElements = static_cast<int>(elements.coordinateLimits.size() + elements.springs.size() +
                                            elements.bushings.size() + elements.huntCrossley.size());
    return census;
}

}  // namespace sinew
