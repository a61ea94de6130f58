#include "interrupt.hpp"

#include <atomic>
#include <csignal>

namespace drape::app {

namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_signal(int) { g_interrupted = 1; }

}  // namespace

void install_interrupt_handlers() {
    static std::atomic<bool> installed{false};
    if (installed.exchange(true)) return;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
}

bool interrupted() { return g_interrupted != 0; }

}  // namespace drape::app
