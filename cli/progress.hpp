#pragma once
// A progress line on stderr: redrawn in place on a terminal, one line per 10% otherwise (logs, CI).
#include <string>

namespace sinew::cli {

class Progress {
public:
    Progress(std::string label, double total);
    void update(double done);
    void finish();

private:
    std::string label_;
    double total_;
    bool terminal_;
    int lastShown_ = -1;
};

}  // namespace sinew::cli
