// physics/step_clock.h: simulated time advances in fixed steps of 1 / step_hz only, never by a
// wall-clock dt. Step k runs from k / step_hz to (k + 1) / step_hz. A headless frame takes exactly
// round(step_hz / fps) steps; the window spends real time in whole steps, at most a cap a frame
// (beyond it the simulation slows down instead of spiralling).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace wisp {

class StepClock {
public:
    explicit StepClock(float stepHz = 120.0f) : stepHz_(stepHz) {}

    float stepHz() const { return stepHz_; }
    float stepSeconds() const { return 1.0f / stepHz_; }
    uint64_t stepsDone() const { return done_; }
    // Simulated seconds at the end of the steps done.
    double seconds() const { return double(done_) / double(stepHz_); }
    // When step k starts (SimStep.time) and ends (where its pose is taken).
    float stepStart(uint64_t k) const { return float(k) * stepSeconds(); }
    double stepEnd(uint64_t k) const { return double(k + 1) / double(stepHz_); }

    // Steps in one frame of a run at `fps` frames per simulated second: round(step_hz / fps), at least 1.
    uint32_t stepsPerFrame(float fps) const { return std::max(1u, uint32_t(std::lround(stepHz_ / fps))); }
    // The whole steps `realSeconds` more of real time make due, at most `cap` (then the rest is dropped).
    uint32_t stepsDue(double realSeconds, uint32_t cap)
    {
        pending_ += realSeconds;
        uint32_t due = uint32_t(pending_ / double(stepSeconds()));
        pending_ -= double(due) * double(stepSeconds());
        if (due > cap) {
            due = cap;
            pending_ = 0.0;
        }
        return due;
    }

    void advance(uint64_t steps) { done_ += steps; }
    // A new rate from the next step on (the steps done so far count at the old one: time runs on).
    void setStepHz(float stepHz)
    {
        done_ = uint64_t(std::llround(seconds() * double(stepHz)));
        stepHz_ = stepHz;
    }

private:
    float stepHz_;
    uint64_t done_ = 0;
    double pending_ = 0.0; // real seconds not yet spent in a step
};

} // namespace wisp
