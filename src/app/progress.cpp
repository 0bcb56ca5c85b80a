#include "app/progress.h"

#include <unistd.h>

#include <cstdio>

namespace cloth::app {

Progress::Progress(long total, bool enabled)
    : total_(total),
      enabled_(enabled && isatty(STDERR_FILENO)),
      start_(Clock::now()),
      lastDraw_(start_) {}

void Progress::update(long done) {
    if (!enabled_) return;
    const auto now = Clock::now();
    // Quiet for the first half second (short runs show nothing), then ten redraws a second.
    if (now - start_ < std::chrono::milliseconds(500) ||
        now - lastDraw_ < std::chrono::milliseconds(100))
        return;
    lastDraw_ = now;
    const double fraction = double(done) / double(total_);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const int width = 30, filled = int(fraction * width);
    char bar[width + 1];
    for (int k = 0; k < width; ++k) bar[k] = k < filled ? '#' : '.';
    bar[width] = '\0';
    std::fprintf(stderr, "\r[%s] %3d%%  step %ld/%ld  eta %.1f s ", bar, int(fraction * 100), done,
                 total_, fraction > 0 ? elapsed * (1 - fraction) / fraction : 0.0);
    std::fflush(stderr);
    drawn_ = true;
}

void Progress::finish() {
    if (drawn_) std::fputs("\r\033[K", stderr);
}

}  // namespace cloth::app
