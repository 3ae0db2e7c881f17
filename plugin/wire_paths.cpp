#include "sinew/plugin/wire_paths.hpp"

#include <algorithm>
#include <string>

#include "eigen_simtk.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/wire_path.hpp"

namespace sinew {

void copyPositionKinematics(const SimTK::SimbodyMatterSubsystem& matter,
                            const std::vector<SimTK::MobilizedBodyIndex>& bodies, const Model& model,
                            const SimTK::State& state, Data& data) {
    const SimTK::Vector& q = state.getQ();
    for (int i = 0; i < q.size(); ++i) data.q[i] = q[i];
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (model.getLink(i).isVirtual) continue;
        const std::size_t b = static_cast<std::size_t>(i);
        const SimTK::MobilizedBody& body = matter.getMobilizedBody(bodies[b]);
        const SimTK::Transform& X_GB = body.getBodyTransform(state);
        data.R_GB[b] = toEigen(X_GB.R());
        data.p_GB[b] = toEigen(X_GB.p());
        // The joint's F frame on the parent body, and the joint centre (M's origin) on this one.
        const SimTK::Transform X_GF = body.getParentMobilizedBody().getBodyTransform(state) * body.getInboardFrame(state);
        data.R_GF[b] = toEigen(X_GF.R());
        data.p_GM[b] = toEigen(X_GB * body.getOutboardFrame(state).p());
        const Joint& joint = model.getJoint(i);
        if (joint.type != JointType::Custom) continue;
        for (int c = 0; c < joint.nu; ++c) {
            const SimTK::SpatialVec H_FM = body.getH_FMCol(state, SimTK::MobilizerUIndex(c));
            data.H_FM[b].col(c) << H_FM[0][0], H_FM[0][1], H_FM[0][2], H_FM[1][0], H_FM[1][1], H_FM[1][2];
        }
    }
}

void copyVelocityKinematics(const SimTK::SimbodyMatterSubsystem& matter,
                            const std::vector<SimTK::MobilizedBodyIndex>& bodies, const Model& model,
                            const SimTK::State& state, Data& data) {
    const SimTK::Vector& u = state.getU();
    for (int i = 0; i < u.size(); ++i) data.u[i] = u[i];
    for (int i = 0; i < model.getNumLinks(); ++i) {
        if (model.getLink(i).isVirtual) continue;
        const std::size_t b = static_cast<std::size_t>(i);
        const SimTK::SpatialVec& V_GB = matter.getMobilizedBody(bodies[b]).getBodyVelocity(state);
        data.w_GB[b] = toEigen(V_GB[0]);
        data.v_GB[b] = toEigen(V_GB[1]);
    }
}

SimbodyWirePaths::SimbodyWirePaths(const SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                   std::vector<SimTK::MobilizedBodyIndex> bodies)
    : SimTK::Subsystem::Guts("sinew wire paths"),
      matter_(matter),
      model_(model),
      bodies_(std::move(bodies)),
      data_(model),
      tensions_(Eigen::VectorXd::Zero(model.getNumWires())) {
    const auto& links = model.getLinks();
    if (std::none_of(links.begin(), links.end(), [](const Link& link) { return link.isVirtual; })) return;
    equilibrium_.emplace(model);
    // The first warm start: the virtual links where the model file puts them, at rest.
    for (int v : equilibrium_->links) {
        const Joint& joint = model.getJoint(v);
        const Eigen::Vector4d w_xyz = model.getDefaultQ().segment<4>(joint.qStart);
        data_.R_GB[static_cast<std::size_t>(v)] =
            Eigen::Quaterniond(w_xyz[0], w_xyz[1], w_xyz[2], w_xyz[3]).normalized().toRotationMatrix();
        data_.p_GB[static_cast<std::size_t>(v)] = model.getDefaultQ().segment<3>(joint.qStart + 4);
    }
}

const SimbodyWirePaths& SimbodyWirePaths::adopt(SimTK::MultibodySystem& system,
                                                const SimTK::SimbodyMatterSubsystem& matter, const Model& model,
                                                std::vector<SimTK::MobilizedBodyIndex> bodies) {
    auto* paths = new SimbodyWirePaths(matter, model, std::move(bodies));
    SimTK::Subsystem handle;
    handle.adoptSubsystemGuts(paths);
    system.adoptSubsystem(handle);  // the system's handle owns it now; `handle` only refers to it
    return *paths;
}

int SimbodyWirePaths::realizeSubsystemTopologyImpl(SimTK::State& state) const {
    pathsEntry_ = allocateLazyCacheEntry(state, SimTK::Stage::Position, new SimTK::Value<long long>(0));
    tensionsEntry_ = allocateLazyCacheEntry(state, SimTK::Stage::Velocity, new SimTK::Value<long long>(0));
    return 0;
}

bool SimbodyWirePaths::holds(const SimTK::State& state, SimTK::CacheEntryIndex entry, long long evaluation) const {
    // (static_cast: the entry is the Value<long long> realizeSubsystemTopologyImpl allocated; Debian's Simbody
    // is built without NDEBUG, where downcast would be a dynamic_cast per wire force element and state.)
    return evaluation != 0 && isCacheValueRealized(state, entry) &&
           static_cast<const SimTK::Value<long long>&>(getCacheEntry(state, entry)).get() == evaluation;
}

void SimbodyWirePaths::mark(const SimTK::State& state, SimTK::CacheEntryIndex entry, long long evaluation) const {
    static_cast<SimTK::Value<long long>&>(updCacheEntry(state, entry)).upd() = evaluation;
    markCacheValueRealized(state, entry);
}

const Data& SimbodyWirePaths::realizePaths(const SimTK::State& state) const {
    if (holds(state, pathsEntry_, pathsEvaluation_)) return data_;
    pathsEvaluation_ = tensionsEvaluation_ = 0;
    copyPositionKinematics(matter_, bodies_, model_, state, data_);
    calcWirePaths(model_, data_);
    pathsEvaluation_ = ++evaluations_;
    mark(state, pathsEntry_, pathsEvaluation_);
    return data_;
}

const Data& SimbodyWirePaths::realizeTensions(const SimTK::State& state) const {
    // Tensions are only ever held for the paths data_ holds, so the state's own entry settles it.
    if (holds(state, tensionsEntry_, tensionsEvaluation_)) return data_;
    realizePaths(state);
    tensionsEvaluation_ = 0;
    const double time = state.getTime();
    copyVelocityKinematics(matter_, bodies_, model_, state, data_);
    calcWireSpeeds(model_, data_);
    try {
        if (equilibrium_) {
            placeBonePointsOfVirtualLinkWires(state);
            calcVirtualLinkEquilibrium(model_, data_, time, *equilibrium_);
        }
        calcWireTensions(model_, data_, time, tensions_);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (at t = " + std::to_string(time) + " s)");
    }
    tensionsEvaluation_ = ++evaluations_;
    mark(state, tensionsEntry_, tensionsEvaluation_);
    return data_;
}

// The solve can be ill-conditioned where a virtual link is nearly slack (a roundoff change of the bones'
// poses can move its udot by 1e-3), so it takes the bones' points exactly where Simbody's station kinematics
// puts them (r = R_GB p_B; p = p_GB + r; v = v_GB + w x r), not as calcWireSpeeds recovers r from p - p_GB:
// the inputs sinew's own engine and Simbody's have long been compared on.
void SimbodyWirePaths::placeBonePointsOfVirtualLinkWires(const SimTK::State& state) const {
    const std::vector<WirePoint>& points = model_.getWirePoints();
    for (int w : equilibrium_->wires) {
        const Wire& wire = model_.getWire(w);
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            if (model_.getLink(points[kk].link).isVirtual) continue;
            SimTK::Vec3 p_G, v_G;
            matter_.getMobilizedBody(bodies_[static_cast<std::size_t>(points[kk].link)])
                .findStationLocationAndVelocityInGround(state, toVec3(points[kk].p_B), p_G, v_G);
            data_.p_GP[kk] = toEigen(p_G);
            data_.v_GP[kk] = toEigen(v_G);
        }
    }
}

void SimbodyWirePaths::applyTension(int w, double f, SimTK::Vector_<SimTK::SpatialVec>& bodyForces,
                                    SimTK::Vector& mobilityForces) const {
    const int row = data_.wireGradientRow[static_cast<std::size_t>(w)];
    if (row >= 0) {
        for (int u = 0; u < mobilityForces.size(); ++u) mobilityForces[u] -= f * data_.wireLengthGradient(row, u);
        return;
    }
    auto addPointForce = [&](int link, const Eigen::Vector3d& p_G, const Eigen::Vector3d& dLdp_G) {
        if (model_.getLink(link).isVirtual) return;
        const std::size_t b = static_cast<std::size_t>(link);
        const Eigen::Vector3d f_G = -f * dLdp_G;
        bodyForces[bodies_[b]] += SimTK::SpatialVec(toVec3((p_G - data_.p_GB[b]).cross(f_G)), toVec3(f_G));
    };
    const Wire& wire = model_.getWire(w);
    if (wire.isPolyline()) {
        const std::vector<WirePoint>& points = model_.getWirePoints();
        for (int k = wire.firstPoint; k < wire.firstPoint + wire.numPoints; ++k) {
            const std::size_t kk = static_cast<std::size_t>(k);
            addPointForce(points[kk].link, data_.p_GP[kk], data_.dLdp_GP[kk]);
        }
        return;
    }
    const Data::WirePathPoint* path = data_.wirePath.data() + data_.wirePathStart[static_cast<std::size_t>(w)];
    for (int i = 0; i < data_.wirePathSize[static_cast<std::size_t>(w)]; ++i)
        addPointForce(path[i].link, path[i].p_G, path[i].dLdp_G);
    for (const WirePointMotion& m : wire.motions) mobilityForces[m.u] -= f * calcWirePointMotionTerm(model_, data_, w, m);
}

}  // namespace sinew
