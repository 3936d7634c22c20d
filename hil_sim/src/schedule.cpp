#include "ntn/hil/schedule.hpp"

#include <algorithm>

namespace ntn::hil {

SenderSchedule::SenderSchedule(std::int64_t period_ns, std::int64_t frames, int resync_after) {
  valid_ = period_ns > 0 && frames > 0 && resync_after >= 0 && resync_after <= kMaxResyncAfter &&
           frames <= kMaxSpan / period_ns;
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
  recent_count_ = 0;
  recent_next_ = 0;
  return true;
}

bool SenderSchedule::observe(const OfferResult& r, std::int64_t current, std::int64_t seen_ns) {
  if (!valid_ || resync_after_ == 0) return false;
  Seen now;
  switch (r.status) {
    case OfferStatus::kCurrent:
    case OfferStatus::kBuffered:
      now.side = 0;  // the schedule works for this packet
      break;
    case OfferStatus::kTooEarly:
      now.side = +1;
      break;
    case OfferStatus::kLate:
      now.side = -1;
      break;
    default:
      return false;  // not a packet of the stream, or nothing about timing
  }
  if (now.side != 0) {
    if (!plausible(r.frame, current) || !epoch_of(r.frame, seen_ns, now.epoch)) return false;
    now.lead = r.frame - current;
  }
  const int window = 2 * resync_after_;
  recent_[static_cast<std::size_t>(recent_next_)] = now;
  recent_next_ = (recent_next_ + 1) % window;
  recent_count_ = std::min(recent_count_ + 1, window);
  if (now.side == 0) return false;
  int agree = 0;
  std::int64_t epoch = now.epoch;
  for (int i = 0; i < recent_count_; ++i) {
    const Seen& s = recent_[static_cast<std::size_t>(i)];
    const std::int64_t d = s.lead > now.lead ? s.lead - now.lead : now.lead - s.lead;
    if (s.side == now.side && d <= kResyncSpread) {
      ++agree;
      epoch = std::min(epoch, s.epoch);
    }
  }
  // K of them, and more than all the other packets of the window together.
  if (agree < resync_after_ || 2 * agree <= recent_count_) return false;
  epoch_ = epoch;
  if (!anchored_) anchor_frame_ = r.frame;
  anchored_ = true;
  ++resyncs_;
  last_resync_frame_ = current;
  flags_ |= flag::kResync;
  recent_count_ = 0;
  recent_next_ = 0;
  return true;
}

}  // namespace ntn::hil
