#include "ntn/hil/schedule.hpp"

#include <algorithm>

namespace ntn::hil {

SenderSchedule::SenderSchedule(std::int64_t period_ns, std::int64_t frames, int resync_after) {
  valid_ = period_ns > 0 && frames > 0 && resync_after >= 0 && frames <= kMaxSpan / period_ns;
  if (!valid_) return;
  period_ns_ = period_ns;
  frames_ = frames;
  resync_after_ = resync_after;
}

bool SenderSchedule::plausible(std::int64_t frame, std::int64_t current) const {
  if (frame < 0 || frame >= frames_ || current < 0 || current >= frames_) return false;
  const std::int64_t distance = frame >= current ? frame - current : current - frame;
  return distance <= InputGate::kFrameWindow;
}

bool SenderSchedule::epoch_of(std::int64_t frame, std::int64_t t, std::int64_t& e) const {
  // frame < frames_ <= kMaxSpan / period_ns_: the product fits.
  const std::int64_t offset = frame * period_ns_;
  if (__builtin_sub_overflow(t, offset, &e)) return false;
  // The loop adds up to frames x period + period / 2 (< 2 kMaxSpan) to it: |e| <= 2^62 keeps
  // every deadline in range.
  constexpr std::int64_t kLimit = std::int64_t{1} << 62;
  return e >= -kLimit && e <= kLimit;
}

bool SenderSchedule::anchor(std::int64_t frame, std::int64_t arrival_ns, std::int64_t current) {
  if (!valid_ || anchored_ || !plausible(frame, current)) return false;
  std::int64_t e = 0;
  if (!epoch_of(frame, arrival_ns, e)) return false;
  epoch_ = e;
  anchored_ = true;
  anchor_frame_ = frame;
  run_side_ = 0, run_length_ = 0;
  return true;
}

bool SenderSchedule::observe(const OfferResult& r, std::int64_t current, std::int64_t seen_ns) {
  if (!valid_) return false;
  int side = 0;
  switch (r.status) {
    case OfferStatus::kCurrent:
    case OfferStatus::kBuffered:
      run_side_ = 0, run_length_ = 0;  // the schedule works for this packet
      return false;
    case OfferStatus::kTooEarly:
      side = +1;
      break;
    case OfferStatus::kLate:
      side = -1;
      break;
    default:
      return false;  // not a packet of the stream, or nothing about timing
  }
  std::int64_t e = 0;
  if (resync_after_ == 0 || !plausible(r.frame, current) || !epoch_of(r.frame, seen_ns, e))
    return false;
  const std::int64_t lead = r.frame - current;
  if (run_length_ > 0 && side == run_side_ &&
      std::max(run_max_lead_, lead) - std::min(run_min_lead_, lead) <= kResyncSpread) {
    ++run_length_;
    run_min_lead_ = std::min(run_min_lead_, lead);
    run_max_lead_ = std::max(run_max_lead_, lead);
    run_epoch_ = std::min(run_epoch_, e);
  } else {
    run_side_ = side, run_length_ = 1;
    run_min_lead_ = run_max_lead_ = lead;
    run_epoch_ = e;
  }
  if (run_length_ < resync_after_) return false;
  epoch_ = run_epoch_;
  if (!anchored_) anchor_frame_ = r.frame;
  anchored_ = true;
  ++resyncs_;
  last_resync_frame_ = current;
  flags_ |= flag::kResync;
  run_side_ = 0, run_length_ = 0;
  return true;
}

}  // namespace ntn::hil
