#include "sinew/signal/signal_filter.hpp"

#include <cmath>
#include <string>

#include "sinew/core/error.hpp"

namespace sinew {

Eigen::VectorXd padSignal(const Eigen::Ref<const Eigen::VectorXd>& signal, int padSize) {
    const Eigen::Index n = signal.size();
    if (padSize < 0 || (padSize > 0 && padSize > n - 1))
        throw Error("padSignal: pad size " + std::to_string(padSize) + " for " + std::to_string(n) +
                    " samples; expected 0 to size - 1 (the reflection needs that many samples beyond the end one)");
    Eigen::VectorXd padded(n + 2 * padSize);
    padded.segment(padSize, n) = signal;
    for (int k = 1; k <= padSize; ++k) {
        padded(padSize - k) = 2 * signal(0) - signal(k);
        padded(padSize + n - 1 + k) = 2 * signal(n - 1) - signal(n - 1 - k);
    }
    return padded;
}

LowpassIIRCoefficients calcLowpassIIRCoefficients(double samplePeriod, double cutoffHz) {
    if (!(std::isfinite(samplePeriod) && samplePeriod > 0))
        throw Error("lowpassIIR: sample period " + std::to_string(samplePeriod) + " s; expected a finite value > 0");
    if (!(std::isfinite(cutoffHz) && cutoffHz > 0))
        throw Error("lowpassIIR: cutoff frequency " + std::to_string(cutoffHz) +
                    " Hz; expected a finite value > 0 (no filtering is the caller's choice, not a zero cutoff)");
    LowpassIIRCoefficients c;
    // OpenSim's Signal::LowpassIIR lowers a cutoff at or above Nyquist to 0.49 of the sampling rate.
    const double samplingHz = 1 / samplePeriod;
    c.cutoffHz = cutoffHz >= 0.5 * samplingHz ? 0.49 * samplingHz : cutoffHz;
    // H(s) = W^3 / ((s + W)(s^2 + W s + W^2)) with s = (1 - 1/z)/(1 + 1/z) and the pre-warped cutoff
    // W = tan(pi fc T); expanding numerator and denominator in powers of 1/z (docs/signal-processing.md).
    const double w = std::tan(M_PI * c.cutoffHz * samplePeriod);
    const double w2 = w * w, w3 = w2 * w;
    const double d0 = (w + 1) * (w2 + w + 1);
    c.numerator = {w3 / d0, 3 * w3 / d0, 3 * w3 / d0, w3 / d0};
    c.denominator = {1, (3 * w3 + 2 * w2 - 2 * w - 3) / d0, (3 * w3 - 2 * w2 - 2 * w + 3) / d0,
                     (w - 1) * (w2 - w + 1) / d0};
    return c;
}

namespace {

// One causal pass over `x` into `y`; the first three outputs are the inputs (OpenSim's start-up).
void runPass(const LowpassIIRCoefficients& c, const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::VectorXd& y) {
    const Eigen::Index n = x.size();
    y.head<3>() = x.head<3>();
    for (Eigen::Index i = 3; i < n; ++i) {
        double value = 0;
        for (int k = 0; k < 4; ++k) value += c.numerator[k] * x(i - k);
        for (int k = 1; k < 4; ++k) value -= c.denominator[k] * y(i - k);
        y(i) = value;
    }
}

}  // namespace

Eigen::VectorXd lowpassIIR(const Eigen::Ref<const Eigen::VectorXd>& signal, double samplePeriod, double cutoffHz) {
    if (signal.size() < 4)
        throw Error("lowpassIIR: " + std::to_string(signal.size()) + " samples; the filter needs at least 4");
    for (Eigen::Index i = 0; i < signal.size(); ++i)
        if (!std::isfinite(signal(i)))
            throw Error("lowpassIIR: sample " + std::to_string(i) + " is not finite");
    const LowpassIIRCoefficients c = calcLowpassIIRCoefficients(samplePeriod, cutoffHz);
    Eigen::VectorXd forward(signal.size());
    runPass(c, signal, forward);
    // The backward pass is a causal pass over the time-reversed forward output, reversed back.
    const Eigen::VectorXd reversed = forward.reverse();
    Eigen::VectorXd backward(signal.size());
    runPass(c, reversed, backward);
    return backward.reverse();
}

}  // namespace sinew
