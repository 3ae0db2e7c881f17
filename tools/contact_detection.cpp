#include "sinew/tools/contact_detection.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "sinew/core/data.hpp"
#include "sinew/core/error.hpp"
#include "sinew/core/kinematics.hpp"

namespace sinew {
namespace {

constexpr double kNoHeight = std::numeric_limits<double>::infinity();

void checkInputs(const Model& model, const Eigen::MatrixXd& q, const Eigen::MatrixXd& u,
                 const ContactDetectionOptions& options) {
    if (q.cols() != model.getNumQ() || u.cols() != model.getNumU() || q.rows() != u.rows())
        throw Error("contact detection: q is " + std::to_string(q.rows()) + " x " + std::to_string(q.cols()) +
                    " and u " + std::to_string(u.rows()) + " x " + std::to_string(u.cols()) +
                    ", expected frames x nq (" + std::to_string(model.getNumQ()) + ") and frames x nu (" +
                    std::to_string(model.getNumU()) + ")");
    if (!(model.getGravity().norm() > 0))
        throw Error("contact detection: model '" + model.getName() + "' has no gravity, so the ground has no 'up'");
    if (!(options.heightThreshold >= 0) || !(options.speedThreshold >= 0))
        throw Error("contact detection: the height and speed thresholds must be >= 0");
}

// The lowest height a slow sole vertex reaches: a foot passing low but fast (a toe swept under the body by an
// inverse-kinematics fit) is no evidence of the floor, a resting one is. The lowest of all when none is slow.
double estimateFloor(const Eigen::MatrixXd& height, const Eigen::MatrixXd& speed, const ContactDetectionOptions& options) {
    if (height.size() == 0) return 0;
    const double lowestSlow = (speed.array() <= options.speedThreshold).select(height, kNoHeight).minCoeff();
    return lowestSlow < kNoHeight ? lowestSlow : height.minCoeff();
}

}  // namespace

ContactDetection detectContacts(const Model& model, const Eigen::MatrixXd& q, const Eigen::MatrixXd& u,
                                const ContactDetectionOptions& options) {
    checkInputs(model, q, u, options);
    const Eigen::Vector3d up = -model.getGravity().normalized();
    const std::vector<Contact>& contacts = model.getContacts();
    int numVertices = 0;
    for (const Contact& contact : contacts) numVertices += static_cast<int>(contact.sole_B.size());
    const Eigen::Index frames = q.rows();
    // Every vertex's height and speed per frame (frames x vertices, contact-major).
    Eigen::MatrixXd height(frames, numVertices), speed(frames, numVertices);
    Data data(model);
    for (Eigen::Index i = 0; i < frames; ++i) {
        calcPositionKinematics(model, data, q.row(i).transpose());
        calcVelocityKinematics(model, data, u.row(i).transpose());
        int column = 0;
        for (const Contact& contact : contacts) {
            const std::size_t b = static_cast<std::size_t>(contact.link);
            for (const Eigen::Vector3d& p_B : contact.sole_B) {
                const Eigen::Vector3d r_G = data.R_GB[b] * p_B;
                height(i, column) = up.dot(data.p_GB[b] + r_G);
                speed(i, column++) = (data.v_GB[b] + data.w_GB[b].cross(r_G)).norm();
            }
        }
    }
    ContactDetection detection;
    detection.floorHeight = std::isnan(options.floorHeight) ? estimateFloor(height, speed, options) : options.floorHeight;
    detection.inContact.assign(static_cast<std::size_t>(frames), std::vector<char>(contacts.size(), 0));
    detection.lowestHeight.resize(frames, static_cast<Eigen::Index>(contacts.size()));
    detection.lowestSpeed.resize(frames, static_cast<Eigen::Index>(contacts.size()));
    for (Eigen::Index i = 0; i < frames; ++i) {
        int first = 0;
        for (std::size_t c = 0; c < contacts.size(); ++c) {
            const int n = static_cast<int>(contacts[c].sole_B.size());
            Eigen::Index lowest;
            detection.lowestHeight(i, c) = height.row(i).segment(first, n).minCoeff(&lowest) - detection.floorHeight;
            double slowest = speed(i, first + lowest);
            bool touching = false;
            for (int v = first; v < first + n; ++v) {
                if (height(i, v) - detection.floorHeight > options.heightThreshold) continue;
                slowest = touching ? std::fmin(slowest, speed(i, v)) : speed(i, v);
                touching = true;
            }
            detection.lowestSpeed(i, c) = slowest;
            detection.inContact[static_cast<std::size_t>(i)][c] = touching && slowest <= options.speedThreshold;
            first += n;
        }
    }
    return detection;
}

}  // namespace sinew
