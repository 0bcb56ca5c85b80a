// A progress bar on stderr, drawn only when stderr is a terminal and the run is long enough
// for it to matter.
#pragma once

#include <chrono>

namespace cloth::app {

class Progress {
public:
    Progress(long total, bool enabled);
    void update(long done);
    void finish();

private:
    using Clock = std::chrono::steady_clock;
    long total_;
    bool enabled_, drawn_ = false;
    Clock::time_point start_, lastDraw_;
};

}  // namespace cloth::app
