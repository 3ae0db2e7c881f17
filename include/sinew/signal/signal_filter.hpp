#pragma once
// Sampled-signal conditioning as OpenSim 4.4 does it before inverse dynamics: reflect-and-negate padding
// (Signal::Pad) and the 3rd-order Butterworth low-pass run forward then backward (Signal::LowpassIIR).
// Conventions, their sources and the frequency response are in docs/signal-processing.md.
#include <Eigen/Core>
#include <array>

namespace sinew {

// Prepends and appends `padSize` samples, each the point reflection of a sample about the end sample
// (s[-k] = 2 s[0] - s[k], s[n-1+k] = 2 s[n-1] - s[n-1-k]), which keeps the end value and slope and so
// gives a filter a smooth run-in. The same operation pads a time column. Throws sinew::Error unless
// 0 <= padSize <= size - 1. Returns size + 2 padSize samples.
Eigen::VectorXd padSignal(const Eigen::Ref<const Eigen::VectorXd>& signal, int padSize);

// One pass of the 3rd-order Butterworth low-pass, bilinear transform with frequency pre-warping:
//   y[i] = sum_k numerator[k] x[i-k] - sum_{k>=1} denominator[k] y[i-k],  denominator[0] = 1.
struct LowpassIIRCoefficients {
    double cutoffHz = 0;  // the cutoff actually used: the request, or 0.49 of the sampling rate if that is lower
    std::array<double, 4> numerator{};
    std::array<double, 4> denominator{};
};

// Throws sinew::Error unless samplePeriod > 0 and cutoffHz > 0 (both finite). A cutoff at or above the
// Nyquist frequency is lowered to 0.49 / samplePeriod, as OpenSim does.
LowpassIIRCoefficients calcLowpassIIRCoefficients(double samplePeriod, double cutoffHz);

// Zero-phase low-pass: the Butterworth pass forward, then backward over the result, so the magnitude
// response is 1 / (1 + (tan(pi f T) / tan(pi fc T))^6) and the gain at the cutoff is 1/2. As in OpenSim,
// each pass copies its first three input samples unchanged and starts the recursion from them (pad the
// signal first). Throws sinew::Error for fewer than 4 samples or a non-finite sample.
Eigen::VectorXd lowpassIIR(const Eigen::Ref<const Eigen::VectorXd>& signal, double samplePeriod, double cutoffHz);

}  // namespace sinew
