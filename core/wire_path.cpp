#include "sinew/core/wire_path.hpp"

#include "sinew/core/error.hpp"

namespace sinew {

void calcWirePaths(const Model& model, Data& data) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t b = static_cast<std::size_t>(points[k].link);
        data.p_GP[k] = data.p_GB[b] + data.R_GB[b] * points[k].p_B;
    }
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        const std::size_t first = static_cast<std::size_t>(wire.firstPoint);
        const std::size_t last = first + static_cast<std::size_t>(wire.numPoints) - 1;
        double length = 0;
        Eigen::Vector3d e_in = Eigen::Vector3d::Zero();
        for (std::size_t k = first; k < last; ++k) {
            const Eigen::Vector3d segment = data.p_GP[k + 1] - data.p_GP[k];
            const double l = segment.norm();
            length += l;
            // A segment that has collapsed to a point has no direction; it then pulls on neither end.
            const Eigen::Vector3d e_out = l > 1e-12 ? Eigen::Vector3d(segment / l) : Eigen::Vector3d::Zero();
            data.dLdp_GP[k] = e_in - e_out;
            e_in = e_out;
        }
        data.dLdp_GP[last] = e_in;
        data.wireLength[w] = length;
    }
}

void calcWireSpeeds(const Model& model, Data& data) {
    const std::vector<WirePoint>& points = model.getWirePoints();
    for (std::size_t k = 0; k < points.size(); ++k) {
        const std::size_t b = static_cast<std::size_t>(points[k].link);
        data.v_GP[k] = data.v_GB[b] + data.w_GB[b].cross(data.p_GP[k] - data.p_GB[b]);
    }
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        double speed = 0;
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k)
            speed += data.dLdp_GP[static_cast<std::size_t>(k)].dot(data.v_GP[static_cast<std::size_t>(k)]);
        data.wireSpeed[w] = speed;
    }
}

void calcWireTensions(const Model& model, const Data& data, double time, Eigen::Ref<Eigen::VectorXd> tensions) {
    for (int w = 0; w < model.getNumWires(); ++w) {
        const Wire& wire = model.getWire(w);
        try {
            tensions[w] = wire.law->calcTension(WireState{data.wireLength[w], data.wireSpeed[w], time});
        } catch (const Error& e) {
            throw Error("wire '" + wire.name + "': " + e.what());
        }
    }
}

double calcWirePotentialEnergy(const Model& model, const Data& data) {
    double energy = 0;
    for (int w = 0; w < model.getNumWires(); ++w) energy += model.getWire(w).law->calcPotentialEnergy(data.wireLength[w]);
    return energy;
}

}  // namespace sinew
