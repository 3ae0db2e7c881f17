#pragma once
// Two independent steps of a tool run at once (reading the model while the motion is read, fitting one
// table's splines while another is processed). Private to sinew_tools.
#include <functional>

namespace sinew {

// Runs `first` and `second` on two threads of OpenMP's pool, or one after the other where no second thread
// is free (inside another parallel region), and returns when both have finished. If either throws, first's
// error is rethrown, else second's: the one that running them in turn would have reported.
// OpenMP's threads outlive the call and stay on their cores; a thread started per call (std::async) was
// left by this VM's scheduler on its parent's core, and the two steps took as long as in turn.
void runSideBySide(const std::function<void()>& first, const std::function<void()>& second);

}  // namespace sinew
