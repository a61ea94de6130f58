// Small helpers of the C++ C API tests.
#pragma once

#include <drape/drape.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

namespace drape::test {

/// This thread's last error message.
inline std::string last_error() { return drape_last_error_message(); }

/// A JSON string from the library, parsed and freed.
inline nlohmann::json take_json(char* text) {
    REQUIRE(text != nullptr);
    const nlohmann::json j = nlohmann::json::parse(text);
    drape_free(text);
    return j;
}

/// Cancels a long call from another thread, as a host's UI would, once the call's monitor
/// reports `stage` at `step`, and measures how soon the call returns after the flag is set
/// (`latency`) against the interval between the two reports before (`interval`).
class CancelProbe {
public:
    CancelProbe(std::string stage, int64_t step) : stage_(std::move(stage)), step_(step) {
        REQUIRE(drape_cancel_flag_create(&flag_) == DRAPE_OK);
        monitor_.struct_size = sizeof monitor_;
        REQUIRE(drape_monitor_init(&monitor_) == DRAPE_OK);
        monitor_.user = this;
        monitor_.cancel = flag_;
        monitor_.progress = [](void* user, const drape_progress* p) -> int32_t {
            auto* self = static_cast<CancelProbe*>(user);
            const Clock::time_point now = Clock::now();
            if (self->stage_ == p->stage && p->step == self->step_ && !self->armed_) {
                self->interval_ = std::chrono::duration<double>(now - self->previous_).count();
                self->armed_ = true;
            }
            self->previous_ = now;
            return 1;
        };
    }
    ~CancelProbe() { drape_cancel_flag_destroy(flag_); }
    CancelProbe(const CancelProbe&) = delete;
    CancelProbe& operator=(const CancelProbe&) = delete;

    const drape_monitor* monitor() const { return &monitor_; }

    /// Runs `call` (which passes monitor() to the library) with the cancelling thread beside it.
    template <class Call>
    drape_status run(Call&& call) {
        std::thread canceller([this] {
            while (!armed_ && !done_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            if (done_) return;
            at_ = Clock::now();
            drape_cancel_flag_set(flag_);
        });
        const drape_status st = call();
        const Clock::time_point returned = Clock::now();
        done_ = true;
        canceller.join();
        latency_ = std::chrono::duration<double>(returned - at_).count();
        return st;
    }
    bool armed() const { return armed_; }
    double latency() const { return latency_; }
    double interval() const { return interval_; }

private:
    using Clock = std::chrono::steady_clock;
    std::string stage_;
    int64_t step_;
    drape_cancel_flag flag_ = nullptr;
    drape_monitor monitor_{};
    std::atomic<bool> armed_{false}, done_{false};
    Clock::time_point at_{}, previous_{};
    double interval_ = 0, latency_ = 0;
};

}  // namespace drape::test
